//! Display names of entities (a glTF node's name, say), for lists and messages.

use std::fmt;

/// An entity's display name. A component; names need not be unique.
#[derive(Clone, Debug, Default, PartialEq, Eq, Hash)]
pub struct Name(pub String);

impl Name {
    /// A name from anything string-like.
    pub fn new(name: impl Into<String>) -> Self {
        Self(name.into())
    }
}

impl fmt::Display for Name {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}
