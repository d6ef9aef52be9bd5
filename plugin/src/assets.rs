//! Typed asset storage with reference-counted handles.

use std::fmt;
use std::hash::{Hash, Hasher};
use std::marker::PhantomData;
use std::sync::{Arc, Weak};

/// A copyable, non-owning id of an asset in an [`Assets`] store. A stale id (its asset was
/// freed, maybe its slot reused) finds nothing.
pub struct AssetId<T> {
    index: u32,
    generation: u32,
    marker: PhantomData<fn() -> T>,
}

impl<T> AssetId<T> {
    /// The slot index, for display and hashing.
    pub fn index(&self) -> u32 {
        self.index
    }
}

impl<T> Clone for AssetId<T> {
    fn clone(&self) -> Self {
        *self
    }
}
impl<T> Copy for AssetId<T> {}
impl<T> PartialEq for AssetId<T> {
    fn eq(&self, other: &Self) -> bool {
        self.index == other.index && self.generation == other.generation
    }
}
impl<T> Eq for AssetId<T> {}
impl<T> Hash for AssetId<T> {
    fn hash<H: Hasher>(&self, state: &mut H) {
        self.index.hash(state);
        self.generation.hash(state);
    }
}
impl<T> PartialOrd for AssetId<T> {
    fn partial_cmp(&self, other: &Self) -> Option<std::cmp::Ordering> {
        Some(self.cmp(other))
    }
}
impl<T> Ord for AssetId<T> {
    fn cmp(&self, other: &Self) -> std::cmp::Ordering {
        (self.index, self.generation).cmp(&(other.index, other.generation))
    }
}
impl<T> fmt::Debug for AssetId<T> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let name = std::any::type_name::<T>();
        let short = name.rsplit("::").next().unwrap_or(name);
        write!(f, "AssetId<{short}>({}v{})", self.index, self.generation)
    }
}

/// A strong reference to an asset: the asset lives while any clone of its handle does, and is
/// freed by the next [`Assets::free_unused`] after the last one is dropped.
pub struct Handle<T> {
    id: AssetId<T>,
    // Shared with the store as a `Weak`; its strong count is the number of live handles.
    liveness: Arc<()>,
}

impl<T> Handle<T> {
    /// The asset's id.
    pub fn id(&self) -> AssetId<T> {
        self.id
    }
}

impl<T> Clone for Handle<T> {
    fn clone(&self) -> Self {
        Self {
            id: self.id,
            liveness: Arc::clone(&self.liveness),
        }
    }
}
impl<T> PartialEq for Handle<T> {
    fn eq(&self, other: &Self) -> bool {
        self.id == other.id
    }
}
impl<T> Eq for Handle<T> {}
impl<T> Hash for Handle<T> {
    fn hash<H: Hasher>(&self, state: &mut H) {
        self.id.hash(state);
    }
}
impl<T> fmt::Debug for Handle<T> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "Handle({:?})", self.id)
    }
}

struct Slot<T> {
    generation: u32,
    entry: Option<Entry<T>>,
}

struct Entry<T> {
    value: T,
    liveness: Weak<()>,
    version: u64,
}

/// A store of assets of type `T` (meshes, images), addressed by [`Handle`] or [`AssetId`].
///
/// Every mutable access bumps the asset's [`version`](Assets::version), which is how the
/// renderer knows what to upload again.
///
/// # Example
/// ```
/// let mut meshes = pom::Assets::<String>::default();
/// let handle = meshes.add("a".to_owned());
/// assert_eq!(meshes.get(&handle).map(String::as_str), Some("a"));
/// let id = handle.id();
/// drop(handle);
/// assert_eq!(meshes.free_unused(), 1);
/// assert!(meshes.get(id).is_none());
/// ```
pub struct Assets<T> {
    slots: Vec<Slot<T>>,
    free: Vec<u32>,
    next_version: u64,
}

impl<T> Default for Assets<T> {
    fn default() -> Self {
        Self {
            slots: Vec::new(),
            free: Vec::new(),
            next_version: 1,
        }
    }
}

impl<T> fmt::Debug for Assets<T> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Assets").field("len", &self.len()).finish()
    }
}

/// Anything that names an asset: a handle or an id.
pub trait AssetRef<T> {
    /// The id it names.
    fn asset_id(&self) -> AssetId<T>;
}
impl<T> AssetRef<T> for AssetId<T> {
    fn asset_id(&self) -> AssetId<T> {
        *self
    }
}
impl<T> AssetRef<T> for Handle<T> {
    fn asset_id(&self) -> AssetId<T> {
        self.id
    }
}
impl<T, R: AssetRef<T>> AssetRef<T> for &R {
    fn asset_id(&self) -> AssetId<T> {
        (*self).asset_id()
    }
}

impl<T> Assets<T> {
    /// Stores `value` and returns the first strong handle to it.
    pub fn add(&mut self, value: T) -> Handle<T> {
        let liveness = Arc::new(());
        let version = self.bump_version();
        let entry = Entry {
            value,
            liveness: Arc::downgrade(&liveness),
            version,
        };
        let index = match self.free.pop() {
            Some(index) => {
                let slot = &mut self.slots[index as usize];
                slot.generation = slot.generation.wrapping_add(1);
                slot.entry = Some(entry);
                index
            }
            None => {
                self.slots.push(Slot {
                    generation: 0,
                    entry: Some(entry),
                });
                (self.slots.len() - 1) as u32
            }
        };
        let generation = self.slots[index as usize].generation;
        Handle {
            id: AssetId {
                index,
                generation,
                marker: PhantomData,
            },
            liveness,
        }
    }

    fn bump_version(&mut self) -> u64 {
        let version = self.next_version;
        self.next_version += 1;
        version
    }

    fn entry(&self, id: AssetId<T>) -> Option<&Entry<T>> {
        self.slots
            .get(id.index as usize)
            .filter(|slot| slot.generation == id.generation)
            .and_then(|slot| slot.entry.as_ref())
    }

    /// The asset, if it still exists.
    pub fn get(&self, asset: impl AssetRef<T>) -> Option<&T> {
        self.entry(asset.asset_id()).map(|entry| &entry.value)
    }

    /// The asset mutably, if it still exists; marks it changed.
    pub fn get_mut(&mut self, asset: impl AssetRef<T>) -> Option<&mut T> {
        let id = asset.asset_id();
        let version = self.next_version;
        let entry = self
            .slots
            .get_mut(id.index as usize)
            .filter(|slot| slot.generation == id.generation)
            .and_then(|slot| slot.entry.as_mut())?;
        entry.version = version;
        self.next_version += 1;
        Some(&mut entry.value)
    }

    /// A number that grows every time the asset is added or mutably accessed.
    pub fn version(&self, asset: impl AssetRef<T>) -> Option<u64> {
        self.entry(asset.asset_id()).map(|entry| entry.version)
    }

    /// The asset and its [`version`](Assets::version), if it still exists, in one lookup.
    pub fn get_with_version(&self, asset: impl AssetRef<T>) -> Option<(&T, u64)> {
        self.entry(asset.asset_id())
            .map(|entry| (&entry.value, entry.version))
    }

    /// Whether the asset still exists.
    pub fn contains(&self, asset: impl AssetRef<T>) -> bool {
        self.entry(asset.asset_id()).is_some()
    }

    /// A count that grows with every asset added or borrowed mutably: where two counts are
    /// equal, no asset was added or changed in between.
    pub fn changes(&self) -> u64 {
        self.next_version
    }

    /// Number of stored assets.
    pub fn len(&self) -> usize {
        self.slots
            .iter()
            .filter(|slot| slot.entry.is_some())
            .count()
    }

    /// Whether the store is empty.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Every stored asset with its id.
    pub fn iter(&self) -> impl Iterator<Item = (AssetId<T>, &T)> {
        self.slots.iter().enumerate().filter_map(|(index, slot)| {
            slot.entry.as_ref().map(|entry| {
                (
                    AssetId {
                        index: index as u32,
                        generation: slot.generation,
                        marker: PhantomData,
                    },
                    &entry.value,
                )
            })
        })
    }

    /// Every stored asset mutably, each marked changed.
    pub fn iter_mut(&mut self) -> impl Iterator<Item = (AssetId<T>, &mut T)> {
        let first_version = self.next_version;
        self.next_version += self.slots.len() as u64;
        self.slots
            .iter_mut()
            .enumerate()
            .filter_map(move |(index, slot)| {
                let generation = slot.generation;
                slot.entry.as_mut().map(|entry| {
                    entry.version = first_version + index as u64;
                    (
                        AssetId {
                            index: index as u32,
                            generation,
                            marker: PhantomData,
                        },
                        &mut entry.value,
                    )
                })
            })
    }

    /// Frees every asset that no [`Handle`] refers to any more; returns how many were freed.
    /// Runs every frame in [`crate::Stage::PostUpdate`] for stores that plugins registered.
    pub fn free_unused(&mut self) -> usize {
        let mut freed = 0;
        for (index, slot) in self.slots.iter_mut().enumerate() {
            let unused = slot
                .entry
                .as_ref()
                .is_some_and(|entry| entry.liveness.strong_count() == 0);
            if unused {
                slot.entry = None;
                self.free.push(index as u32);
                freed += 1;
            }
        }
        freed
    }
}

/// A system that calls [`Assets::free_unused`] on the `Assets<T>` resource, if there is one.
pub fn free_unused_assets<T: 'static>(_: &mut hecs::World, resources: &mut crate::Resources) {
    if let Some(assets) = resources.get_mut::<Assets<T>>() {
        assets.free_unused();
    }
}
