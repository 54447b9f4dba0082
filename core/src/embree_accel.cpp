#include "pierce/embree_accel.h"

#include "pierce/embree_query.h"

#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>

namespace pierce {

namespace {

struct BoundsData {
  const HugePageVector<Triangle<float>>* tris;
  float pad;
};

void bounds_cb(const RTCBoundsFunctionArguments* args) {
  const auto* d = static_cast<const BoundsData*>(args->geometryUserPtr);
  const Triangle<float>& t = (*d->tris)[args->primID];
  const Vec3f lo = vmin(vmin(t.v0, t.v1), t.v2), hi = vmax(vmax(t.v0, t.v1), t.v2);
  RTCBounds* b = args->bounds_o;
  b->lower_x = lo.x - d->pad, b->lower_y = lo.y - d->pad, b->lower_z = lo.z - d->pad;
  b->upper_x = hi.x + d->pad, b->upper_y = hi.y + d->pad, b->upper_z = hi.z + d->pad;
}

void occluded_noop(const RTCOccludedFunctionNArguments*) {}

}  // namespace

void attach_native_triangles(RTCDevice device, RTCScene target, const Scene& scene, DegenerateTriangles degenerate) {
  for (const Geometry& geo : scene.geometries()) {
    RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                          3 * sizeof(float), geo.vertices.size()));
    for (std::size_t i = 0; i < geo.vertices.size(); ++i) {
      v[3 * i] = float(geo.vertices[i].x), v[3 * i + 1] = float(geo.vertices[i].y),
                v[3 * i + 2] = float(geo.vertices[i].z);
    }
    auto* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                               3 * sizeof(unsigned), geo.triangles.size()));
    const bool leave_out = degenerate == DegenerateTriangles::leave_out;
    for (std::size_t i = 0; i < geo.triangles.size(); ++i)
      for (int k = 0; k < 3; ++k)
        idx[3 * i + k] = leave_out && geo.degenerate[i] ? unsigned(geo.vertices.size()) : geo.triangles[i][k];
    rtcCommitGeometry(g);
    rtcAttachGeometry(target, g);  // ids 0, 1, ... in attachment order
    rtcReleaseGeometry(g);
  }
}

EmbreeAccel::EmbreeAccel(const Scene& scene, TriangleSource tris) : scene_(&scene), tris_source_(std::move(tris)) {
  device_ = rtcNewDevice("threads=0");
  if (!device_) throw std::runtime_error("Embree: rtcNewDevice failed");
  max_abs_ = scene.bounds().max_abs_coord();
  // 2^-14 of the scene's magnitude: well above Embree's rounding in its box test for origins
  // rebased near the scene, negligible for traversal cost.
  pad_ = float(std::ldexp(std::max(max_abs_, 1e-30), -14));
}

RTCScene EmbreeAccel::exact() const {
  std::call_once(exact_once_, [this] { build_exact(); });
  return exact_;
}

const HugePageVector<Triangle<float>>& EmbreeAccel::tris() const {
  std::call_once(exact_once_, [this] { build_exact(); });
  return *tris_;
}

RTCScene EmbreeAccel::native() const {
  std::call_once(native_once_, [this] { build_native(); });
  return native_;
}

// A failed build leaves nothing behind (std::call_once runs again after an exception, afresh).
void EmbreeAccel::build_exact() const {
  const HugePageVector<Triangle<float>>& tris = tris_source_();
  RTCScene scene = rtcNewScene(device_);
  rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_HIGH);
  std::unique_ptr<BoundsData> data;
  if (!tris.empty()) {
    RTCGeometry g = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_USER);
    rtcSetGeometryUserPrimitiveCount(g, unsigned(tris.size()));
    data = std::make_unique<BoundsData>(BoundsData{&tris, pad_});
    rtcSetGeometryUserData(g, data.get());
    rtcSetGeometryBoundsFunction(g, bounds_cb, nullptr);
    rtcSetGeometryOccludedFunction(g, occluded_noop);
    rtcSetGeometryIntersectFunction(g, detail::embree_exact_intersect);
    rtcCommitGeometry(g);
    rtcAttachGeometry(scene, g);
    rtcReleaseGeometry(g);
  }
  rtcCommitScene(scene);
  committed(scene, "building the exact scene");
  exact_ = scene;
  tris_ = &tris;
  bounds_data_ = data.release();
}

void EmbreeAccel::build_native() const {
  RTCScene scene = rtcNewScene(device_);
  try {
    attach_native_triangles(device_, scene, *scene_, DegenerateTriangles::leave_out);
  } catch (...) {
    rtcReleaseScene(scene);
    throw;
  }
  rtcCommitScene(scene);
  committed(scene, "building the native scene");
  native_ = scene;
}

void EmbreeAccel::committed(RTCScene scene, const char* what) const {
  const RTCError e = rtcGetDeviceError(device_);
  if (e == RTC_ERROR_NONE) return;
  rtcReleaseScene(scene);
  throw std::runtime_error(std::string("Embree error ") + std::to_string(int(e)) + " in " + what);
}

EmbreeAccel::~EmbreeAccel() {
  if (exact_) rtcReleaseScene(exact_);
  delete static_cast<BoundsData*>(bounds_data_);
  if (native_) rtcReleaseScene(native_);
  if (device_) rtcReleaseDevice(device_);
}

}  // namespace pierce
