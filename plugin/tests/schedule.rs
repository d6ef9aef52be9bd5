//! The stage-ordering rules of `App::update` and the plugin lifecycle.

use std::cell::RefCell;
use std::rc::Rc;

use hecs::World;
use pom::{App, AppError, Plugin, Resources, Stage};

type Log = Rc<RefCell<Vec<&'static str>>>;

fn logger(log: &Log, entry: &'static str) -> impl FnMut(&mut World, &mut Resources) + 'static {
    let log = Rc::clone(log);
    move |_, _| log.borrow_mut().push(entry)
}

#[test]
fn stages_run_in_declared_order_whatever_order_systems_were_added_in() {
    let log = Log::default();
    let mut app = App::new();
    for (stage, name) in Stage::ALL.iter().rev().zip([
        "render", "prepare", "extract", "post", "update", "pre", "startup",
    ]) {
        app.add_system(*stage, logger(&log, name));
    }
    app.update().unwrap();
    assert_eq!(
        *log.borrow(),
        [
            "startup", "pre", "update", "post", "extract", "prepare", "render"
        ]
    );
}

#[test]
fn startup_runs_only_in_the_first_update() {
    let log = Log::default();
    let mut app = App::new();
    app.add_system(Stage::Startup, logger(&log, "startup"));
    app.add_system(Stage::Update, logger(&log, "update"));
    for _ in 0..3 {
        app.update().unwrap();
    }
    assert_eq!(*log.borrow(), ["startup", "update", "update", "update"]);
}

#[test]
fn systems_of_one_stage_run_in_the_order_they_were_added() {
    let log = Log::default();
    let mut app = App::new();
    app.add_system(Stage::Update, logger(&log, "a"));
    app.add_system(Stage::Update, logger(&log, "b"));
    app.add_system(Stage::Update, logger(&log, "c"));
    app.update().unwrap();
    assert_eq!(*log.borrow(), ["a", "b", "c"]);
}

#[derive(Debug, thiserror::Error)]
#[error("boom")]
struct Boom;

fn failing_system(_: &mut World, _: &mut Resources) -> Result<(), Boom> {
    Err(Boom)
}

#[test]
fn a_failing_system_stops_the_update_and_names_itself_and_its_stage() {
    let log = Log::default();
    let mut app = App::new();
    app.add_system(Stage::Update, failing_system);
    app.add_system(Stage::PostUpdate, logger(&log, "post"));
    let error = app.update().unwrap_err();
    assert!(matches!(
        error,
        AppError::System {
            stage: Stage::Update,
            ..
        }
    ));
    let message = error.to_string();
    assert!(
        message.contains("failing_system") && message.contains("boom"),
        "{message}"
    );
    assert!(log.borrow().is_empty(), "later stages were skipped");
}

#[test]
fn a_failing_startup_system_is_not_retried() {
    let log = Log::default();
    let mut app = App::new();
    app.add_system(Stage::Startup, failing_system);
    app.add_system(Stage::Update, logger(&log, "update"));
    assert!(app.update().is_err());
    app.update().unwrap();
    assert_eq!(*log.borrow(), ["update"]);
}

struct Recorder {
    log: Log,
    name: &'static str,
    fail_finish: bool,
}

impl Plugin for Recorder {
    fn build(&self, app: &mut App) {
        self.log.borrow_mut().push(self.name);
        app.add_system(Stage::Update, logger(&self.log, "system"));
    }

    fn finish(&self, _: &mut App) -> Result<(), pom::BoxedError> {
        self.log.borrow_mut().push("finish");
        if self.fail_finish {
            Err("no device".into())
        } else {
            Ok(())
        }
    }
}

#[test]
fn plugins_build_when_added_and_finish_once_before_the_first_update() {
    let log = Log::default();
    let mut app = App::new();
    app.add_plugin(Recorder {
        log: Rc::clone(&log),
        name: "build",
        fail_finish: false,
    });
    assert_eq!(*log.borrow(), ["build"]);
    app.update().unwrap();
    app.update().unwrap();
    assert_eq!(*log.borrow(), ["build", "finish", "system", "system"]);
    assert!(app.has_plugin::<Recorder>());
}

#[test]
fn a_failing_plugin_finish_is_an_error_naming_the_plugin() {
    let log = Log::default();
    let mut app = App::new();
    app.add_plugin(Recorder {
        log,
        name: "build",
        fail_finish: true,
    });
    let error = app.update().unwrap_err();
    assert!(matches!(error, AppError::Plugin { .. }));
    assert!(error.to_string().contains("Recorder") && error.to_string().contains("no device"));
}

#[test]
fn a_function_is_a_plugin() {
    fn add_counter(app: &mut App) {
        app.insert_resource(7_u32);
    }
    let mut app = App::new();
    app.add_plugin(add_counter);
    assert_eq!(app.resources.get::<u32>(), Some(&7));
}
