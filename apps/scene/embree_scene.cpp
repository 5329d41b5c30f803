// embree_scene.cpp - see embree_scene.h.
#include "embree_scene.h"

#include "udm1app/one_line.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace udm1scene {

double ray_offset(Vec3 p, double t)
{
    double m = std::max({std::fabs(p.x), std::fabs(p.y), std::fabs(p.z), std::fabs(t), 0x1p-24});
    return m * 0x1p-18;
}

Segment shadow_segment(Vec3 p, Vec3 n, double t, Vec3 q, Vec3 nq)
{
    Vec3 o = p + (dot(n, q - p) > 0 ? n : -n) * ray_offset(p, t);
    Vec3 e = q + (dot(nq, o - q) > 0 ? nq : -nq) * ray_offset(q);
    Vec3 d = e - o;
    double len = length(d);
    if (!(len > 0)) return {o, Vec3(0, 0, 1), 0.0};
    return {o, d * (1 / len), len};
}

Segment segment_to_infinity(Vec3 p, Vec3 n, double t, Vec3 w)
{
    return {p + (dot(n, w) > 0 ? n : -n) * ray_offset(p, t), w, std::numeric_limits<double>::infinity()};
}

namespace {

// A sphere that is not a sphere in world space (an ellipsoid: Shape::ellipsoid), as an Embree user
// geometry: the ray taken to object space and met with the sphere there in double precision (pbrt-v4's
// Sphere::BasicIntersect: t is the same parameter in both spaces, the map being affine).
void ellipsoid_bounds(const RTCBoundsFunctionArguments *args)
{
    const Shape &s = *(const Shape *)args->geometryUserPtr;
    Vec3 lo, hi;
    sphere_bounds(s, &lo, &hi);
    RTCBounds *b = args->bounds_o;  // widened by a float ulp or so, so that float rounding keeps it outside
    b->lower_x = std::nextafter((float)lo.x, -INFINITY), b->lower_y = std::nextafter((float)lo.y, -INFINITY);
    b->lower_z = std::nextafter((float)lo.z, -INFINITY);
    b->upper_x = std::nextafter((float)hi.x, INFINITY), b->upper_y = std::nextafter((float)hi.y, INFINITY);
    b->upper_z = std::nextafter((float)hi.z, INFINITY);
}

// The nearest t in (tnear, tfar] where o + t d meets ellipsoid s, or -1.
double ellipsoid_hit(const Shape &s, Vec3 o, Vec3 d, double tnear, double tfar)
{
    Vec3 oo = s.object_from_world.point(o), dd = s.object_from_world.vector(d);
    double r = s.object_radius, a = dot(dd, dd), b = 2 * dot(oo, dd), c = dot(oo, oo) - r * r;
    if (!(a > 0)) return -1;
    Vec3 v = oo - dd * (b / (2 * a));  // the discriminant as pbrt-v4 forms it: 4 a (r + |v|)(r - |v|)
    double len = length(v), disc = 4 * a * (r + len) * (r - len);
    if (!(disc >= 0)) return -1;
    double root = std::sqrt(disc), q = b < 0 ? -0.5 * (b - root) : -0.5 * (b + root);
    double t0 = q / a, t1 = q != 0 ? c / q : t0;
    if (t0 > t1) std::swap(t0, t1);
    if (t0 > tnear && t0 <= tfar) return t0;
    if (t1 > tnear && t1 <= tfar) return t1;
    return -1;
}

void ellipsoid_intersect(const RTCIntersectFunctionNArguments *args)
{
    const Shape &s = *(const Shape *)args->geometryUserPtr;
    RTCRayN *ray = RTCRayHitN_RayN(args->rayhit, args->N);
    RTCHitN *hit = RTCRayHitN_HitN(args->rayhit, args->N);
    const unsigned N = args->N;
    for (unsigned i = 0; i < N; ++i) {
        if (args->valid[i] != -1) continue;
        Vec3 o(RTCRayN_org_x(ray, N, i), RTCRayN_org_y(ray, N, i), RTCRayN_org_z(ray, N, i));
        Vec3 d(RTCRayN_dir_x(ray, N, i), RTCRayN_dir_y(ray, N, i), RTCRayN_dir_z(ray, N, i));
        float &tfar = RTCRayN_tfar(ray, N, i);
        double t = ellipsoid_hit(s, o, d, RTCRayN_tnear(ray, N, i), tfar);
        if (!(t >= 0) || !((float)t <= tfar)) continue;
        tfar = (float)t;
        Vec3 n = sphere_normal(s, o + d * t);  // (hit_of makes the normal the renderers use)
        RTCHitN_Ng_x(hit, N, i) = (float)n.x, RTCHitN_Ng_y(hit, N, i) = (float)n.y, RTCHitN_Ng_z(hit, N, i) = (float)n.z;
        RTCHitN_u(hit, N, i) = 0, RTCHitN_v(hit, N, i) = 0;
        RTCHitN_primID(hit, N, i) = args->primID;
        RTCHitN_geomID(hit, N, i) = args->geomID;
        RTCHitN_instID(hit, N, i, 0) = args->context->instID[0];
    }
}

void ellipsoid_occluded(const RTCOccludedFunctionNArguments *args)
{
    const Shape &s = *(const Shape *)args->geometryUserPtr;
    const unsigned N = args->N;
    for (unsigned i = 0; i < N; ++i) {
        if (args->valid[i] != -1) continue;
        RTCRayN *ray = args->ray;
        Vec3 o(RTCRayN_org_x(ray, N, i), RTCRayN_org_y(ray, N, i), RTCRayN_org_z(ray, N, i));
        Vec3 d(RTCRayN_dir_x(ray, N, i), RTCRayN_dir_y(ray, N, i), RTCRayN_dir_z(ray, N, i));
        float &tfar = RTCRayN_tfar(ray, N, i);
        if (ellipsoid_hit(s, o, d, RTCRayN_tnear(ray, N, i), tfar) >= 0) tfar = -INFINITY;
    }
}

}  // namespace

const char *embree_error_name(RTCError code)
{
    switch (code) {
    case RTC_ERROR_NONE: return "RTC_ERROR_NONE";
    case RTC_ERROR_UNKNOWN: return "RTC_ERROR_UNKNOWN";
    case RTC_ERROR_INVALID_ARGUMENT: return "RTC_ERROR_INVALID_ARGUMENT";
    case RTC_ERROR_INVALID_OPERATION: return "RTC_ERROR_INVALID_OPERATION";
    case RTC_ERROR_OUT_OF_MEMORY: return "RTC_ERROR_OUT_OF_MEMORY";
    case RTC_ERROR_UNSUPPORTED_CPU: return "RTC_ERROR_UNSUPPORTED_CPU";
    case RTC_ERROR_CANCELLED: return "RTC_ERROR_CANCELLED";
    }
    return "an unknown Embree error code";
}

void EmbreeErrors::attach(RTCDevice device) { rtcSetDeviceErrorFunction(device, &EmbreeErrors::record, this); }

void EmbreeErrors::record(void *self, RTCError code, const char *message)
{
    EmbreeErrors &e = *static_cast<EmbreeErrors *>(self);
    std::lock_guard<std::mutex> lock(e.mutex_);
    if (e.count_++ == 0)
        e.first_ = std::string(embree_error_name(code)) + (message && *message ? ": " + udm1app::fold_lines(message) : "");
}

std::string EmbreeErrors::text() const
{
    std::lock_guard<std::mutex> lock(mutex_);
    if (count_ <= 1) return first_;
    return first_ + " (and " + std::to_string(count_ - 1) + " more)";
}

EmbreeScene::EmbreeScene(const Scene &scene, bool robust) : src_(scene)
{
    try {
        build(scene, robust);
    } catch (...) {  // the device and scene made so far: a throwing constructor runs no destructor
        release();
        throw;
    }
}

void EmbreeScene::build(const Scene &scene, bool robust)
{
    device_ = rtcNewDevice("verbose=0");  // errors come to errors_, never printed by Embree
    if (!device_)
        throw SceneError(scene.source + ": Embree could not create a device (" + embree_error_name(rtcGetDeviceError(nullptr)) +
                         ")");
    errors_->attach(device_);
    auto failed = [&](const char *doing) {
        std::string why = errors_->text();
        return SceneError(scene.source + ": Embree could not " + doing + (why.empty() ? "" : ": " + why));
    };
    scene_ = rtcNewScene(device_);
    if (!scene_) throw failed("create a scene");
    rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_HIGH);
    if (robust) rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST);
    for (unsigned k = 0; k < scene.shapes.size(); ++k) {
        const Shape &s = scene.shapes[k];
        RTCGeometry g = rtcNewGeometry(device_, s.kind == Shape::Triangles ? RTC_GEOMETRY_TYPE_TRIANGLE
                                                : s.ellipsoid                 ? RTC_GEOMETRY_TYPE_USER
                                                                              : RTC_GEOMETRY_TYPE_SPHERE_POINT);
        if (!g) throw failed("create a geometry");
        bool filled = false;
        if (s.kind == Shape::Triangles) {
            size_t nv = s.P.size() / 3, nt = s.indices.size() / 3;
            float *v = (float *)rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                        3 * sizeof(float), nv);
            unsigned *i = (unsigned *)rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                              3 * sizeof(unsigned), nt);
            if (v && i) {
                std::copy(s.P.begin(), s.P.end(), v);
                std::copy(s.indices.begin(), s.indices.end(), i);
                filled = true;
            }
        } else if (s.ellipsoid) {
            rtcSetGeometryUserPrimitiveCount(g, 1);
            rtcSetGeometryUserData(g, (void *)&s);
            rtcSetGeometryBoundsFunction(g, ellipsoid_bounds, nullptr);
            rtcSetGeometryIntersectFunction(g, ellipsoid_intersect);
            rtcSetGeometryOccludedFunction(g, ellipsoid_occluded);
            filled = true;
        } else {
            float *v = (float *)rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4,
                                                        4 * sizeof(float), 1);
            if (v) {
                v[0] = (float)s.center.x, v[1] = (float)s.center.y, v[2] = (float)s.center.z, v[3] = (float)s.radius;
                filled = true;
            }
        }
        if (!filled) {
            rtcReleaseGeometry(g);
            throw failed(s.kind == Shape::Triangles ? "allocate a mesh" : "allocate a sphere");
        }
        rtcCommitGeometry(g);
        unsigned id = rtcAttachGeometry(scene_, g);
        rtcReleaseGeometry(g);
        if (shape_of_geom_.size() <= id) shape_of_geom_.resize(id + 1);
        shape_of_geom_[id] = k;
    }
    // every triangle's unit geometric normal, once (24 bytes a triangle): a hit reads it instead of
    // recomputing it from the vertices (udm1-pt: 8-11 % of a Cornell box render)
    size_t triangles = 0;
    for (const Shape &s : scene.shapes)
        if (s.kind == Shape::Triangles) triangles += s.indices.size() / 3;
    normals_.reserve(triangles);
    first_normal_.assign(scene.shapes.size(), 0);
    for (unsigned k = 0; k < scene.shapes.size(); ++k) {
        const Shape &s = scene.shapes[k];
        first_normal_[k] = normals_.size();
        if (s.kind == Shape::Triangles)
            for (unsigned t = 0; t < s.indices.size() / 3; ++t) normals_.push_back(triangle_normal(s, t));
    }
    rtcCommitScene(scene_);
    if (rtcGetDeviceError(device_) != RTC_ERROR_NONE || !errors_->text().empty()) throw failed("build the scene");
    Vec3 lo, hi;
    scene.bounds(&lo, &hi);
    scale_ = std::max({1e-6, std::fabs(lo.x), std::fabs(lo.y), std::fabs(lo.z), std::fabs(hi.x), std::fabs(hi.y),
                       std::fabs(hi.z)});
}

void EmbreeScene::release()
{
    if (scene_) rtcReleaseScene(scene_);
    if (device_) rtcReleaseDevice(device_);
    scene_ = nullptr;
    device_ = nullptr;
}

EmbreeScene::~EmbreeScene() { release(); }

void EmbreeScene::check(const char *doing) const
{
    std::string why = errors_->text();
    if (!why.empty()) throw SceneError(src_.source + ": Embree failed while " + doing + ": " + why);
}

bool EmbreeScene::intersect(Vec3 o, Vec3 d, double tnear, double tfar, Hit *hit) const
{
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    RTCRayHit rh;
    rh.ray.org_x = (float)o.x, rh.ray.org_y = (float)o.y, rh.ray.org_z = (float)o.z;
    rh.ray.dir_x = (float)d.x, rh.ray.dir_y = (float)d.y, rh.ray.dir_z = (float)d.z;
    rh.ray.tnear = (float)tnear;
    rh.ray.tfar = tfar >= 3e38 ? std::numeric_limits<float>::infinity() : (float)tfar;
    rh.ray.mask = 0xFFFFFFFF;
    rh.ray.flags = 0;
    rh.ray.time = 0;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    if (log_)
        log_->push_back({{rh.ray.org_x, rh.ray.org_y, rh.ray.org_z}, {rh.ray.dir_x, rh.ray.dir_y, rh.ray.dir_z},
                         rh.ray.tnear, rh.ray.tfar, false});
    rtcIntersect1(scene_, &ctx, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
    *hit = hit_of(o, d, rh.ray.tfar, rh.hit.geomID, rh.hit.primID, rh.hit.u, rh.hit.v);
    return true;
}

Hit EmbreeScene::hit_of(Vec3 o, Vec3 d, float tfar, unsigned geom_id, unsigned prim_id, float u, float v) const
{
    Hit hit;
    hit.t = tfar;
    hit.shape = shape_of_geom_[geom_id];
    hit.prim = prim_id;
    hit.u = u;
    hit.v = v;
    hit.p = o + d * hit.t;
    const Shape &s = src_.shapes[hit.shape];
    if (s.kind == Shape::Sphere) {
        hit.ng = sphere_normal(s, hit.p);
        if (s.reverse_orientation) hit.ng = -hit.ng;
    } else {
        hit.ng = normals_[first_normal_[hit.shape] + hit.prim];
    }
    return hit;
}

bool EmbreeScene::occluded(Vec3 o, Vec3 d, double tnear, double tfar) const
{
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    RTCRay r;
    r.org_x = (float)o.x, r.org_y = (float)o.y, r.org_z = (float)o.z;
    r.dir_x = (float)d.x, r.dir_y = (float)d.y, r.dir_z = (float)d.z;
    r.tnear = (float)tnear;
    r.tfar = tfar >= 3e38 ? std::numeric_limits<float>::infinity() : (float)tfar;
    r.mask = 0xFFFFFFFF;
    r.flags = 0;
    r.time = 0;
    if (log_) log_->push_back({{r.org_x, r.org_y, r.org_z}, {r.dir_x, r.dir_y, r.dir_z}, r.tnear, r.tfar, true});
    rtcOccluded1(scene_, &ctx, &r);
    return r.tfar < 0;  // Embree sets tfar to -inf on a hit
}

}  // namespace udm1scene
