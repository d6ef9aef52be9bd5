//! A type-keyed map of singletons shared by systems.

use std::any::{Any, TypeId, type_name};
use std::collections::HashMap;

/// A map from a Rust type to the one value of that type the app holds (a "resource").
///
/// # Example
/// ```
/// let mut resources = pom::Resources::default();
/// resources.insert(3_u32);
/// *resources.get_mut::<u32>().unwrap() += 1;
/// assert_eq!(resources.get::<u32>(), Some(&4));
/// ```
#[derive(Default)]
pub struct Resources {
    values: HashMap<TypeId, Box<dyn Any>>,
}

impl Resources {
    /// Inserts `value`, returning the previous value of the same type if there was one.
    pub fn insert<T: 'static>(&mut self, value: T) -> Option<T> {
        self.values
            .insert(TypeId::of::<T>(), Box::new(value))
            .and_then(|old| old.downcast::<T>().ok().map(|boxed| *boxed))
    }

    /// Returns the value of type `T`, if present.
    pub fn get<T: 'static>(&self) -> Option<&T> {
        self.values
            .get(&TypeId::of::<T>())
            .and_then(|value| value.downcast_ref::<T>())
    }

    /// Returns the value of type `T` mutably, if present.
    pub fn get_mut<T: 'static>(&mut self) -> Option<&mut T> {
        self.values
            .get_mut(&TypeId::of::<T>())
            .and_then(|value| value.downcast_mut::<T>())
    }

    /// Returns the value of type `T`, or [`super::AppError::MissingResource`] naming the type:
    /// what a system returns when a plugin it needs was not added.
    pub fn require<T: 'static>(&self) -> Result<&T, super::AppError> {
        self.get::<T>().ok_or_else(super::AppError::missing::<T>)
    }

    /// Like [`Resources::require`], mutably.
    pub fn require_mut<T: 'static>(&mut self) -> Result<&mut T, super::AppError> {
        self.get_mut::<T>()
            .ok_or_else(super::AppError::missing::<T>)
    }

    /// Returns the value of type `T`, inserting `T::default()` first if it is missing.
    pub fn get_or_default<T: Default + 'static>(&mut self) -> &mut T {
        self.values
            .entry(TypeId::of::<T>())
            .or_insert_with(|| Box::new(T::default()))
            .downcast_mut::<T>()
            // The entry is keyed by `TypeId::of::<T>()`, so it always holds a `T`.
            .expect("resource map entry holds a value of its key's type")
    }

    /// Removes and returns the value of type `T`, if present.
    pub fn remove<T: 'static>(&mut self) -> Option<T> {
        self.values
            .remove(&TypeId::of::<T>())
            .and_then(|value| value.downcast::<T>().ok().map(|boxed| *boxed))
    }

    /// Whether a value of type `T` is present.
    pub fn contains<T: 'static>(&self) -> bool {
        self.values.contains_key(&TypeId::of::<T>())
    }

    /// The types of the values present.
    pub(crate) fn type_ids(&self) -> impl Iterator<Item = TypeId> + '_ {
        self.values.keys().copied()
    }

    /// Drops the value of the type `id`, if present.
    pub(crate) fn remove_type_id(&mut self, id: TypeId) {
        self.values.remove(&id);
    }

    /// Runs `f` with `T` taken out of the map, so `f` may borrow other resources mutably at the
    /// same time; `T` is put back afterwards. Returns `None` when `T` is missing.
    ///
    /// # Example
    /// ```
    /// let mut resources = pom::Resources::default();
    /// resources.insert(2_u32);
    /// resources.insert(String::from("x"));
    /// resources.scope(|resources, count: &mut u32| {
    ///     resources.get_mut::<String>().unwrap().push_str(&count.to_string());
    /// });
    /// assert_eq!(resources.get::<String>().unwrap(), "x2");
    /// ```
    /// `T` goes back even when `f` panics (the guard's drop puts it back while unwinding).
    pub fn scope<T: 'static, R>(&mut self, f: impl FnOnce(&mut Self, &mut T) -> R) -> Option<R> {
        scoped(self, f)
    }

    /// [`Resources::scope`] for a fallible `f`: a missing `T` is the error
    /// [`AppError::missing`](super::AppError::missing) names it with.
    pub fn require_scope<T: 'static, R>(
        &mut self,
        f: impl FnOnce(&mut Self, &mut T) -> Result<R, super::AppError>,
    ) -> Result<R, super::AppError> {
        scoped(self, f).unwrap_or_else(|| Err(super::AppError::missing::<T>()))
    }

    /// The type name of `T`, for error messages about a missing resource.
    pub(crate) fn name_of<T: 'static>() -> &'static str {
        type_name::<T>()
    }
}

/// Whatever holds the resources a scope borrows from: [`Resources`] itself, or the app.
pub(crate) trait ResourceHolder {
    /// The resources.
    fn resources_mut(&mut self) -> &mut Resources;
}

impl ResourceHolder for Resources {
    fn resources_mut(&mut self) -> &mut Resources {
        self
    }
}

/// Takes `T` out of `holder`'s resources for `f` and puts it back when `f` returns, fails or
/// panics (the guard's drop runs while unwinding): [`Resources::scope`] and
/// [`crate::App::resource_scope`]. The value stays in its box: a scope moves and allocates
/// nothing, however large `T` is.
pub(crate) fn scoped<H: ResourceHolder, T: 'static, R>(
    holder: &mut H,
    f: impl FnOnce(&mut H, &mut T) -> R,
) -> Option<R> {
    struct PutBack<'a, H: ResourceHolder> {
        holder: &'a mut H,
        value: Option<Box<dyn Any>>,
    }
    impl<H: ResourceHolder> Drop for PutBack<'_, H> {
        fn drop(&mut self) {
            if let Some(value) = self.value.take() {
                // Keyed by the value's own type, which is the scope's `T`.
                let key = (*value).type_id();
                self.holder.resources_mut().values.insert(key, value);
            }
        }
    }
    let value = holder.resources_mut().values.remove(&TypeId::of::<T>())?;
    let mut guard = PutBack {
        holder,
        value: Some(value),
    };
    let PutBack { holder, value } = &mut guard;
    let value = value.as_mut()?.downcast_mut::<T>()?;
    Some(f(holder, value))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_scope_leaves_the_value_where_it_is() {
        let mut resources = Resources::default();
        resources.insert([7_u8; 64]);
        let at = |value: &[u8; 64]| value.as_ptr() as usize;
        let before = at(resources.get::<[u8; 64]>().unwrap());
        let during = resources.scope(|_, value: &mut [u8; 64]| at(value));
        assert_eq!(during, Some(before));
        assert_eq!(at(resources.get::<[u8; 64]>().unwrap()), before);
    }

    #[test]
    fn insert_replaces_and_returns_previous_value() {
        let mut resources = Resources::default();
        assert_eq!(resources.insert(1_i32), None);
        assert_eq!(resources.insert(2_i32), Some(1));
        assert_eq!(resources.get::<i32>(), Some(&2));
        assert!(resources.get::<u8>().is_none());
    }

    #[test]
    fn scope_puts_the_value_back() {
        let mut resources = Resources::default();
        resources.insert(vec![1_u8]);
        let length = resources.scope(|_, v: &mut Vec<u8>| {
            v.push(2);
            v.len()
        });
        assert_eq!(length, Some(2));
        assert_eq!(resources.get::<Vec<u8>>(), Some(&vec![1, 2]));
        assert_eq!(resources.scope(|_, _: &mut f32| ()), None);
    }

    #[test]
    fn scope_puts_the_value_back_when_the_work_panics() {
        let mut resources = Resources::default();
        resources.insert(7_u32);
        let outcome = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
            resources.scope(|_, _: &mut u32| panic!("the work failed"))
        }));
        assert!(outcome.is_err());
        assert_eq!(resources.get::<u32>(), Some(&7));
    }
}
