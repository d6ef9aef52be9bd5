//! The integration tests that can share a process, as modules of one test binary: each test
//! binary links wgpu and pom again (tens of megabytes and seconds of linking each), so one binary
//! keeps a CI machine's disk and time. A test that measures or owns something of the whole
//! process (its memory, its logger, its panic hook, the files beside its binary) is a binary of
//! its own: tests/Cargo.toml lists them.

mod anti_aliasing;
mod bench_reproducible;
mod blend_order;
mod code_shape;
mod comment_hygiene;
mod custom_material;
mod deferred_path;
mod dynamic_height;
mod ensure_vulkan;
mod environment_light;
mod gltf_as_authored;
mod gltf_layers;
mod gltf_lights;
mod gltf_loading;
mod gltf_scene_values;
mod gltf_triplanar;
mod golden_scenes;
mod gpu_errors;
mod gpu_timing;
mod layered_parallax;
mod layering;
mod macro_errors;
mod many_lights;
mod max_mip;
mod max_mip_edges;
mod parallax_accuracy;
mod parallax_depth_and_units;
mod parallax_geometry;
mod parallax_golden;
mod parallax_lod;
mod parallax_robustness;
mod parameter_round_trip;
mod pipeline_compilation;
mod post_filter;
mod render_features;
mod render_phases;
mod renderer;
mod scene_scripts;
mod scene_shadows;
mod scene_test_docs;
mod scratch_game;
mod script_expectations;
mod script_materials;
mod script_statistics;
mod script_values;
mod seed_port;
mod shader_hot_reload;
mod shaders;
mod silhouette;
mod soft_shadow_jitter;
mod split_view;
mod still_scene;
mod street_corner;
mod tangent_frames;
mod terrain_mesh;
mod test_binaries;
mod triplanar_parallax;
