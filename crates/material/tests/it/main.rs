//! The `material` crate's integration tests, one module per file, built as one test binary
//! (one link instead of 22: CI's disk and time). Run one file's tests with
//! `cargo test -p material --test it <module>::`.

mod mdl_support;
mod support;

mod area_lights;
mod base;
mod bsdf_builtin;
mod glossy;
mod maya_analytic;
mod maya_exports;
mod maya_file_filter;
mod maya_final_gather;
mod maya_irradiance;
mod maya_materials;
mod maya_path;
mod maya_ramp;
mod maya_solid_textures;
mod maya_stand_in_lines;
mod maya_textures2d;
mod maya_textures3d;
mod maya_utilities;
mod maya_vector_product;
mod mdl_base_conversions;
mod mdl_base_functions;
mod mdl_combinators;
mod mdl_compile;
mod mdl_furnace;
mod mdl_hit;
mod mdl_hit_loops;
mod mdl_hit_matrices;
mod mdl_layer_normals;
mod mdl_layers;
mod mdl_matrices;
mod mdl_measured_bsdf;
mod mdl_measured_edf;
mod mdl_measured_factor;
mod mdl_microfacet_params;
mod mdl_per_hit;
mod mdl_per_hit_curves;
mod mdl_ptex;
mod mdl_rough_transmission;
mod mdl_state_space;
mod mdl_statements;
mod mdl_textures3d;
mod mdl_vdf_tints;
mod mdl_volume;
mod mdl_volume_textures;
mod mdl_wide;
mod mia;
mod mib_glossy_translation;
mod model;
mod photometric;
mod stand_in;
mod sun_and_sky;
mod texture_filter;
