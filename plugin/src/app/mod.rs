//! The app: a world of entities, resources, a staged schedule of systems, and plugins.

mod resources;

pub use resources::Resources;

use std::error::Error;
use std::fmt;

use hecs::World;

/// The boxed error a fallible system or plugin returns.
pub type BoxedError = Box<dyn Error + Send + Sync + 'static>;

/// The named phases of one [`App::update`], run in declaration order.
///
/// [`Stage::Startup`] runs only in the first update; every other stage runs every update.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Stage {
    /// Once, before anything else in the first update: spawn the initial scene.
    Startup,
    /// Before game logic: input, time.
    PreUpdate,
    /// Game and user logic.
    Update,
    /// After game logic: transform propagation, asset bookkeeping.
    PostUpdate,
    /// Copy what the renderer needs out of the world.
    Extract,
    /// Upload what changed to the GPU.
    Prepare,
    /// Record and submit the frame's passes.
    Render,
}

impl Stage {
    /// Every stage, in the order [`App::update`] runs them.
    pub const ALL: [Stage; 7] = [
        Stage::Startup,
        Stage::PreUpdate,
        Stage::Update,
        Stage::PostUpdate,
        Stage::Extract,
        Stage::Prepare,
        Stage::Render,
    ];

    fn index(self) -> usize {
        self as usize
    }
}

/// A unit of work run once per update in its stage.
pub trait System: 'static {
    /// A name for error messages: the function's type name unless set otherwise.
    fn name(&self) -> &str;
    /// Runs the system once.
    fn run(&mut self, world: &mut World, resources: &mut Resources) -> Result<(), BoxedError>;
}

/// Conversion of a plain function or closure into a [`System`].
///
/// Both `fn(&mut World, &mut Resources)` and
/// `fn(&mut World, &mut Resources) -> Result<(), E>` are systems; `Marker` only tells the two apart.
pub trait IntoSystem<Marker> {
    /// Boxes `self` as a system.
    fn into_system(self) -> Box<dyn System>;
}

/// Marker for systems that cannot fail.
pub struct Infallible;
/// Marker for systems that return a `Result`.
pub struct Fallible;

struct FunctionSystem<F> {
    name: &'static str,
    function: F,
}

impl<F> System for FunctionSystem<F>
where
    F: FnMut(&mut World, &mut Resources) -> Result<(), BoxedError> + 'static,
{
    fn name(&self) -> &str {
        self.name
    }

    fn run(&mut self, world: &mut World, resources: &mut Resources) -> Result<(), BoxedError> {
        (self.function)(world, resources)
    }
}

impl<F> IntoSystem<Infallible> for F
where
    F: FnMut(&mut World, &mut Resources) + 'static,
{
    fn into_system(mut self) -> Box<dyn System> {
        Box::new(FunctionSystem {
            name: std::any::type_name::<F>(),
            function: move |world: &mut World, resources: &mut Resources| {
                self(world, resources);
                Ok(())
            },
        })
    }
}

impl<F, E> IntoSystem<Fallible> for F
where
    F: FnMut(&mut World, &mut Resources) -> Result<(), E> + 'static,
    E: Into<BoxedError>,
{
    fn into_system(mut self) -> Box<dyn System> {
        Box::new(FunctionSystem {
            name: std::any::type_name::<F>(),
            function: move |world: &mut World, resources: &mut Resources| {
                self(world, resources).map_err(Into::into)
            },
        })
    }
}

/// Systems grouped by [`Stage`]; within a stage they run in the order they were added.
#[derive(Default)]
pub struct Schedule {
    stages: [Vec<Box<dyn System>>; Stage::ALL.len()],
    startup_done: bool,
}

impl Schedule {
    /// Appends `system` to `stage`.
    pub fn add_system<M>(&mut self, stage: Stage, system: impl IntoSystem<M>) {
        self.stages[stage.index()].push(system.into_system());
    }

    /// Number of systems in `stage`.
    pub fn len(&self, stage: Stage) -> usize {
        self.stages[stage.index()].len()
    }

    /// Runs the systems of one stage, in order. Stops at the first failing system.
    pub fn run_stage(
        &mut self,
        stage: Stage,
        world: &mut World,
        resources: &mut Resources,
    ) -> Result<(), AppError> {
        for system in &mut self.stages[stage.index()] {
            system
                .run(world, resources)
                .map_err(|source| AppError::System {
                    stage,
                    system: system.name().to_owned(),
                    source,
                })?;
        }
        Ok(())
    }

    /// Runs every stage once (Startup only the first time). Stops at the first failing system.
    pub fn run(&mut self, world: &mut World, resources: &mut Resources) -> Result<(), AppError> {
        for stage in Stage::ALL {
            if stage == Stage::Startup {
                if self.startup_done {
                    continue;
                }
                // Mark first so a failing startup system is not re-run every frame.
                self.startup_done = true;
            }
            self.run_stage(stage, world, resources)?;
        }
        Ok(())
    }
}

/// Something that configures an [`App`]: adds systems, resources and other plugins.
///
/// A plain `fn(&mut App)` is a plugin too.
pub trait Plugin: 'static {
    /// Adds the plugin's systems and resources. Runs when the plugin is added.
    fn build(&self, app: &mut App);

    /// Setup that needs other plugins' resources, typically the GPU device: runs once, in the
    /// order plugins were added, from [`App::finish`] (called by the first [`App::update`]).
    fn finish(&self, _app: &mut App) -> Result<(), BoxedError> {
        Ok(())
    }

    /// The plugin's name in error messages.
    fn name(&self) -> &str {
        std::any::type_name::<Self>()
    }
}

impl<F: Fn(&mut App) + 'static> Plugin for F {
    fn build(&self, app: &mut App) {
        self(app)
    }
}

/// What can go wrong while finishing plugins or running an update.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum AppError {
    /// A plugin's GPU-dependent setup failed.
    #[error("plugin {plugin} failed to finish its setup: {source}")]
    Plugin {
        /// The plugin's type name.
        plugin: String,
        /// What went wrong.
        source: BoxedError,
    },
    /// A system returned an error; the rest of that update was skipped.
    #[error("system {system} in stage {stage:?} failed: {source}")]
    System {
        /// The stage the system ran in.
        stage: Stage,
        /// The system's name.
        system: String,
        /// What went wrong.
        source: BoxedError,
    },
    /// A system or caller needed a resource that no plugin inserted.
    #[error("missing resource {0}: add the plugin that provides it")]
    MissingResource(&'static str),
}

impl AppError {
    /// The error for a missing resource of type `T`.
    pub fn missing<T: 'static>() -> Self {
        AppError::MissingResource(Resources::name_of::<T>())
    }
}

impl resources::ResourceHolder for App {
    fn resources_mut(&mut self) -> &mut Resources {
        &mut self.resources
    }
}

/// The container of everything: the ECS world, the resources, the schedule and the plugins.
///
/// # Example
/// ```
/// use pom::{App, Stage};
/// let mut app = App::new();
/// app.insert_resource(0_u32);
/// app.add_system(Stage::Update, |_: &mut hecs::World, res: &mut pom::Resources| {
///     *res.get_mut::<u32>().unwrap() += 1;
/// });
/// app.update().unwrap();
/// app.update().unwrap();
/// assert_eq!(app.resources.get::<u32>(), Some(&2));
/// ```
#[derive(Default)]
pub struct App {
    /// The entities and their components.
    pub world: World,
    /// Singletons shared between systems.
    pub resources: Resources,
    /// The systems, by stage.
    pub schedule: Schedule,
    plugins: Vec<Box<dyn Plugin>>,
    finished_plugins: usize,
    /// The resources [`Plugin::finish`] made: what [`App::redo_plugin_setup`] drops.
    setup_resources: Vec<std::any::TypeId>,
}

impl fmt::Debug for App {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("App")
            .field("entities", &self.world.len())
            .field(
                "plugins",
                &self.plugins.iter().map(|p| p.name()).collect::<Vec<_>>(),
            )
            .finish_non_exhaustive()
    }
}

impl App {
    /// An empty app with no plugins.
    pub fn new() -> Self {
        Self::default()
    }

    /// Builds `plugin` into the app now and keeps it for [`App::finish`]. A plugin of a type
    /// already added is ignored, with a warning: its systems would otherwise run twice.
    pub fn add_plugin(&mut self, plugin: impl Plugin) -> &mut Self {
        if self
            .plugins
            .iter()
            .any(|added| added.name() == plugin.name())
        {
            log::warn!("plugin {} was already added: ignored", plugin.name());
            return self;
        }
        plugin.build(self);
        self.plugins.push(Box::new(plugin));
        self
    }

    /// Whether a plugin of type `P` was added.
    pub fn has_plugin<P: Plugin>(&self) -> bool {
        let name = std::any::type_name::<P>();
        self.plugins.iter().any(|plugin| plugin.name() == name)
    }

    /// Appends a system to a stage.
    pub fn add_system<M>(&mut self, stage: Stage, system: impl IntoSystem<M>) -> &mut Self {
        self.schedule.add_system(stage, system);
        self
    }

    /// Inserts a resource, replacing any of the same type.
    pub fn insert_resource<T: 'static>(&mut self, value: T) -> &mut Self {
        self.resources.insert(value);
        self
    }

    /// Runs `f` with the resource `T` taken out of the app, so `f` may use the whole app (run
    /// stages, say) while holding it; `T` is put back afterwards, also when `f` fails or panics.
    /// Returns `None` when `T` is missing. The app's version of [`Resources::scope`].
    pub fn resource_scope<T: 'static, R>(
        &mut self,
        f: impl FnOnce(&mut App, &mut T) -> R,
    ) -> Option<R> {
        resources::scoped(self, f)
    }

    /// Runs [`Plugin::finish`] for every plugin that has not been finished yet, in the order
    /// they were added. Called by [`App::update`]; call it yourself to see setup errors early.
    pub fn finish(&mut self) -> Result<(), AppError> {
        while self.finished_plugins < self.plugins.len() {
            let plugin = std::mem::replace(
                &mut self.plugins[self.finished_plugins],
                Box::new(|_: &mut App| {}),
            );
            let before: std::collections::HashSet<_> = self.resources.type_ids().collect();
            let result = plugin.finish(self);
            let made = self.resources.type_ids().filter(|id| !before.contains(id));
            self.setup_resources.extend(made.collect::<Vec<_>>());
            let name = plugin.name().to_owned();
            self.plugins[self.finished_plugins] = plugin;
            self.finished_plugins += 1;
            result.map_err(|source| AppError::Plugin {
                plugin: name,
                source,
            })?;
        }
        Ok(())
    }

    /// Drops the resources every [`Plugin::finish`] made, inserts `fresh`, and runs every
    /// plugin's `finish` again. For a new GPU device after the old one was lost, `fresh` is its
    /// [`crate::GpuContext`]: pipelines, targets and GPU copies of assets are then made on it,
    /// while the assets themselves (CPU side), the world and every other resource stay. GPU
    /// objects a game keeps must be made in a `finish` to survive this.
    pub fn redo_plugin_setup<T: 'static>(&mut self, fresh: T) -> Result<(), AppError> {
        for id in std::mem::take(&mut self.setup_resources) {
            self.resources.remove_type_id(id);
        }
        self.resources.insert(fresh);
        self.finished_plugins = 0;
        self.finish()
    }

    /// Finishes any new plugins, advances the [`crate::Time`] resource (inserting a real-time
    /// one if the app has none), then runs every stage once.
    pub fn update(&mut self) -> Result<(), AppError> {
        self.finish()?;
        self.resources
            .get_or_default::<crate::Time>()
            .advance(std::time::Instant::now());
        self.schedule.run(&mut self.world, &mut self.resources)
    }

    /// Runs only `stages`, in the given order (after [`App::finish`]): to render the same
    /// world again, say, with Extract, Prepare and Render.
    pub fn run_stages(&mut self, stages: &[Stage]) -> Result<(), AppError> {
        self.finish()?;
        for stage in stages {
            self.schedule
                .run_stage(*stage, &mut self.world, &mut self.resources)?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn resource_scope_puts_the_value_back_even_when_the_work_panics() {
        let mut app = App::new();
        app.insert_resource(5_u32);
        let seen = app.resource_scope(|app, value: &mut u32| {
            assert!(app.resources.get::<u32>().is_none(), "taken out meanwhile");
            *value += 1;
            *value
        });
        assert_eq!(seen, Some(6));
        let outcome = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
            app.resource_scope(|_, _: &mut u32| panic!("the work failed"))
        }));
        assert!(outcome.is_err());
        assert_eq!(app.resources.get::<u32>(), Some(&6));
        assert_eq!(app.resource_scope(|_, _: &mut f32| ()), None);
    }

    #[test]
    fn a_plugin_added_twice_is_built_once() {
        fn count(app: &mut App) {
            *app.resources.get_or_default::<u32>() += 1;
        }
        let mut app = App::new();
        app.add_plugin(count).add_plugin(count);
        assert_eq!(app.resources.get::<u32>(), Some(&1));
    }

    #[test]
    fn redoing_the_plugin_setup_remakes_what_finish_made_and_keeps_the_rest() {
        /// Stands for a GPU device: `finish` builds its "pipeline" from it.
        struct Device(u32);
        struct Pipeline(u32);
        struct Setup;
        impl Plugin for Setup {
            fn build(&self, app: &mut App) {
                app.insert_resource(String::from("built"));
            }
            fn finish(&self, app: &mut App) -> Result<(), BoxedError> {
                let device = app.resources.require::<Device>()?.0;
                app.insert_resource(Pipeline(device));
                Ok(())
            }
        }
        let mut app = App::new();
        app.insert_resource(Device(1)).add_plugin(Setup);
        app.update().unwrap();
        app.insert_resource(7_u8);
        assert_eq!(app.resources.get::<Pipeline>().map(|p| p.0), Some(1));
        app.redo_plugin_setup(Device(2)).unwrap();
        assert_eq!(app.resources.get::<Pipeline>().map(|p| p.0), Some(2));
        assert_eq!(app.resources.get::<String>().unwrap(), "built");
        assert_eq!(
            app.resources.get::<u8>(),
            Some(&7),
            "resources made elsewhere stay"
        );
    }
}
