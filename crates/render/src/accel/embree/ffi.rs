//! The few declarations of Embree 3.13's C API that mira calls (`embree3.h`, one instance
//! level): handles, constants, the ray and hit structures and the functions. The calls and
//! their preconditions are in the parent module.

use std::ffi::c_void;
use std::os::raw::{c_char, c_uint};

pub(super) type RtcDevice = *mut c_void;
pub(super) type RtcScene = *mut c_void;
pub(super) type RtcGeometry = *mut c_void;

pub(super) const GEOMETRY_TYPE_TRIANGLE: c_uint = 0;
pub(super) const GEOMETRY_TYPE_QUAD: c_uint = 1;
pub(super) const GEOMETRY_TYPE_INSTANCE: c_uint = 121;
pub(super) const BUFFER_TYPE_INDEX: c_uint = 0;
pub(super) const BUFFER_TYPE_VERTEX: c_uint = 1;
pub(super) const FORMAT_UINT3: c_uint = 0x5003;
pub(super) const FORMAT_UINT4: c_uint = 0x5004;
pub(super) const FORMAT_FLOAT3: c_uint = 0x9003;
pub(super) const FORMAT_FLOAT3X4_COLUMN_MAJOR: c_uint = 0x9234;
pub(super) const BUILD_QUALITY_MEDIUM: c_uint = 1;
pub(super) const SCENE_FLAG_COMPACT: c_uint = 2;
pub(super) const INVALID_ID: c_uint = c_uint::MAX;

/// `struct RTCIntersectContext` of Embree 3.13 built with one instance level.
#[repr(C)]
pub(super) struct IntersectContext {
    pub(super) flags: c_uint,
    pub(super) filter: *const c_void,
    pub(super) inst_id: [c_uint; 1],
}

/// `struct RTCRay`.
#[repr(C, align(16))]
#[derive(Clone, Copy)]
pub(super) struct RtcRay {
    pub(super) org: [f32; 3],
    pub(super) tnear: f32,
    pub(super) dir: [f32; 3],
    pub(super) time: f32,
    pub(super) tfar: f32,
    pub(super) mask: c_uint,
    pub(super) id: c_uint,
    pub(super) flags: c_uint,
}

/// `struct RTCHit` with one instance level.
#[repr(C, align(16))]
#[derive(Clone, Copy)]
pub(super) struct RtcHit {
    pub(super) ng: [f32; 3],
    pub(super) u: f32,
    pub(super) v: f32,
    pub(super) prim_id: c_uint,
    pub(super) geom_id: c_uint,
    pub(super) inst_id: [c_uint; 1],
}

/// `struct RTCRay8`: eight rays, one array per field.
#[repr(C, align(32))]
pub(super) struct RtcRay8 {
    pub(super) org_x: [f32; 8],
    pub(super) org_y: [f32; 8],
    pub(super) org_z: [f32; 8],
    pub(super) tnear: [f32; 8],
    pub(super) dir_x: [f32; 8],
    pub(super) dir_y: [f32; 8],
    pub(super) dir_z: [f32; 8],
    pub(super) time: [f32; 8],
    pub(super) tfar: [f32; 8],
    pub(super) mask: [c_uint; 8],
    pub(super) id: [c_uint; 8],
    pub(super) flags: [c_uint; 8],
}

/// `struct RTCHit8` with one instance level.
#[repr(C, align(32))]
pub(super) struct RtcHit8 {
    pub(super) ng_x: [f32; 8],
    pub(super) ng_y: [f32; 8],
    pub(super) ng_z: [f32; 8],
    pub(super) u: [f32; 8],
    pub(super) v: [f32; 8],
    pub(super) prim_id: [c_uint; 8],
    pub(super) geom_id: [c_uint; 8],
    pub(super) inst_id: [[c_uint; 8]; 1],
}

/// `struct RTCRayHit8`.
#[repr(C, align(32))]
pub(super) struct RtcRayHit8 {
    pub(super) ray: RtcRay8,
    pub(super) hit: RtcHit8,
}

/// The valid-lane mask of a packet of eight (−1: trace the lane, 0: skip it).
#[repr(C, align(32))]
pub(super) struct Valid8(pub(super) [i32; 8]);

/// `RTC_INTERSECT_CONTEXT_FLAG_COHERENT`: the packet's rays are coherent.
pub(super) const CONTEXT_FLAG_COHERENT: c_uint = 1;

/// `struct RTCRayHit`.
#[repr(C, align(16))]
pub(super) struct RtcRayHit {
    pub(super) ray: RtcRay,
    pub(super) hit: RtcHit,
}

/// `RTCMemoryMonitorFunction`: called by Embree with the bytes it is about to allocate
/// (positive) or has freed (negative); returning `false` would make the allocation fail.
pub(super) type MemoryMonitor = unsafe extern "C" fn(user: *mut c_void, bytes: isize, post: bool) -> bool;

#[link(name = "embree3")]
extern "C" {
    pub(super) fn rtcNewDevice(config: *const c_char) -> RtcDevice;
    pub(super) fn rtcReleaseDevice(device: RtcDevice);
    pub(super) fn rtcSetDeviceMemoryMonitorFunction(device: RtcDevice, monitor: MemoryMonitor, user: *mut c_void);
    pub(super) fn rtcGetDeviceError(device: RtcDevice) -> c_uint;
    pub(super) fn rtcNewScene(device: RtcDevice) -> RtcScene;
    pub(super) fn rtcSetSceneBuildQuality(scene: RtcScene, quality: c_uint);
    pub(super) fn rtcCommitScene(scene: RtcScene);
    pub(super) fn rtcReleaseScene(scene: RtcScene);
    pub(super) fn rtcNewGeometry(device: RtcDevice, kind: c_uint) -> RtcGeometry;
    pub(super) fn rtcSetNewGeometryBuffer(
        geometry: RtcGeometry,
        kind: c_uint,
        slot: c_uint,
        format: c_uint,
        byte_stride: usize,
        item_count: usize,
    ) -> *mut c_void;
    pub(super) fn rtcSetSharedGeometryBuffer(
        geometry: RtcGeometry,
        kind: c_uint,
        slot: c_uint,
        format: c_uint,
        ptr: *const c_void,
        byte_offset: usize,
        byte_stride: usize,
        item_count: usize,
    );
    pub(super) fn rtcSetSceneFlags(scene: RtcScene, flags: c_uint);
    pub(super) fn rtcSetGeometryInstancedScene(geometry: RtcGeometry, scene: RtcScene);
    pub(super) fn rtcSetGeometryTransform(geometry: RtcGeometry, time_step: c_uint, format: c_uint, xfm: *const f32);
    pub(super) fn rtcSetGeometryMask(geometry: RtcGeometry, mask: c_uint);
    pub(super) fn rtcSetGeometryTimeStepCount(geometry: RtcGeometry, count: c_uint);
    pub(super) fn rtcCommitGeometry(geometry: RtcGeometry);
    pub(super) fn rtcAttachGeometryByID(scene: RtcScene, geometry: RtcGeometry, id: c_uint);
    pub(super) fn rtcReleaseGeometry(geometry: RtcGeometry);
    pub(super) fn rtcIntersect1(scene: RtcScene, context: *mut IntersectContext, rayhit: *mut RtcRayHit);
    pub(super) fn rtcOccluded1(scene: RtcScene, context: *mut IntersectContext, ray: *mut RtcRay);
    pub(super) fn rtcIntersect8(
        valid: *const Valid8,
        scene: RtcScene,
        context: *mut IntersectContext,
        rayhit: *mut RtcRayHit8,
    );
    pub(super) fn rtcOccluded8(
        valid: *const Valid8,
        scene: RtcScene,
        context: *mut IntersectContext,
        ray: *mut RtcRay8,
    );
    pub(super) fn rtcIntersect1M(
        scene: RtcScene,
        context: *mut IntersectContext,
        rayhit: *mut RtcRayHit,
        count: c_uint,
        byte_stride: usize,
    );
}
