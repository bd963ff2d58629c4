//! The `render` crate's integration tests, one module per file, built as one test binary
//! (one link instead of 38: CI's disk and time). Run one file's tests with
//! `cargo test -p render --test it <module>::`.

mod support;

mod aerial_perspective;
mod analytic;
mod area_lights;
mod backends;
mod classic;
mod classic_shadows;
mod environment;
mod fgcache;
mod first_shadow_packets;
mod glossy_interpolation;
mod iray_sun_and_sky;
mod maya;
mod maya_ambient_links_path;
mod maya_ambient_path;
mod maya_exports_agree;
mod maya_fog_material_path;
mod maya_fog_path;
mod maya_highlight_path;
mod maya_path;
mod maya_soft_shadows_path;
mod maya_vertex_data;
mod maya_volume_axis_path;
mod maya_volume_dir_path;
mod maya_volume_highlight_path;
mod mdl_classic;
mod mdl_cornell;
mod mdl_measured;
mod mdl_object_space;
mod mdl_spot;
mod mdl_textures3d;
mod mdl_vdf_tints;
mod mdl_wide;
mod media;
mod media_classic;
mod media_entry;
mod media_orthographic;
mod mia_helpers;
mod motion;
mod motion_blur;
mod motion_composed;
mod motion_lights;
mod motion_prepasses;
mod motion_shading;
mod path_materials;
mod photometric;
mod photons;
mod rect_light_paths;
mod shutter_shape;
mod sky;
mod sun_sky_path;
mod volume;
mod world_meshes;
