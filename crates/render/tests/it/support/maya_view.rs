//! The view the Maya path-engine tests share: a square image looking straight down at the
//! ground from 4 above.

/// The `.mi` options, camera and camera instance of a `side` × `side` pixel image looking
/// down −y at the plane y = 0 from (0, 4, 0) (focal 1, aperture 1.2: x and z in ±2.4 on
/// the ground), 2 samples per pixel at most (`samples 0 2`) through a 1-pixel box filter:
/// options "opt", camera instance "cam_inst".
pub fn top_down(side: usize) -> String {
    format!(
        "options \"opt\" samples 0 2 filter box 1 1 end options\n\
         camera \"cam\" focal 1 aperture 1.2 aspect 1 resolution {side} {side} end camera\n\
         instance \"cam_inst\" \"cam\" transform 1 0 0 0  0 0 1 0  0 -1 0 0  0 0 -4 1 end instance"
    )
}
