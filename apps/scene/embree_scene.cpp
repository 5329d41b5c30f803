// embree_scene.cpp - see embree_scene.h.
#include "embree_scene.h"

#include "alpha.h"
#include "bilinear_patch.h"
#include "quadrics.h"
#include "udm1app/one_line.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <type_traits>

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

using GeometryData = EmbreeScene::GeometryData;

void set_bounds(RTCBounds *b, Vec3 lo, Vec3 hi)
{
    // widened by a float ulp or so, so that float rounding keeps the shape inside
    b->lower_x = std::nextafter((float)lo.x, -INFINITY), b->lower_y = std::nextafter((float)lo.y, -INFINITY);
    b->lower_z = std::nextafter((float)lo.z, -INFINITY);
    b->upper_x = std::nextafter((float)hi.x, INFINITY), b->upper_y = std::nextafter((float)hi.y, INFINITY);
    b->upper_z = std::nextafter((float)hi.z, INFINITY);
}

// Quadrics that are not Embree spheres (an ellipsoid, a disk, a cylinder, a sphere with alpha) as Embree
// user geometry: the ray met in the quadric's object space in double precision (quadrics.h).
void quadric_bounds(const RTCBoundsFunctionArguments *args)
{
    const GeometryData &g = *(const GeometryData *)args->geometryUserPtr;
    Vec3 lo, hi;
    shape_bounds(g.rt->scene().shapes[g.shape], &lo, &hi);
    set_bounds(args->bounds_o, lo, hi);
}

// The nearest of a shape's hits along a ray that passes its alpha test (alpha.h): the first sees the ray's
// hash, each later one the hash of the ray continued from the rejected hit before it. Returns its index in
// t, or -1.
int first_visible(const GeometryData &g, int n, const double *t, const double (*uv)[2], unsigned prim, Vec3 o, Vec3 d,
                  float tfar)
{
    const Shape &s = g.rt->scene().shapes[g.shape];
    float ho[3] = {(float)o.x, (float)o.y, (float)o.z}, hd[3] = {(float)d.x, (float)d.y, (float)d.z};
    for (int k = 0; k < n; ++k) {
        if (!((float)t[k] <= tfar)) return -1;
        if (!s.has_alpha()) return k;
        Hit h;
        h.t = t[k], h.shape = g.shape, h.prim = prim, h.p = o + d * t[k];
        h.u = uv ? (float)uv[k][0] : 0.0f, h.v = uv ? (float)uv[k][1] : 0.0f;
        h.ng = g.rt->geometric_normal(h);
        if (g.rt->alpha_passes(h, ho, hd)) return k;
        ho[0] = (float)h.p.x, ho[1] = (float)h.p.y, ho[2] = (float)h.p.z;
    }
    return -1;
}

template <class Args> struct RayOf;
template <> struct RayOf<RTCIntersectFunctionNArguments> {
    static RTCRayN *get(const RTCIntersectFunctionNArguments *a) { return RTCRayHitN_RayN(a->rayhit, a->N); }
};
template <> struct RayOf<RTCOccludedFunctionNArguments> {
    static RTCRayN *get(const RTCOccludedFunctionNArguments *a) { return a->ray; }
};

// One callback for both queries and both kinds of user geometry: the hits of each active ray, the first
// visible one reported (intersect) or the ray marked occluded.
template <class Args> void user_query(const Args *args)
{
    constexpr bool occlusion = std::is_same<Args, RTCOccludedFunctionNArguments>::value;
    const GeometryData &g = *(const GeometryData *)args->geometryUserPtr;
    const Shape &s = g.rt->scene().shapes[g.shape];
    RTCRayN *ray = RayOf<Args>::get(args);
    const unsigned N = args->N;
    for (unsigned i = 0; i < N; ++i) {
        if (args->valid[i] != -1) continue;
        Vec3 o(RTCRayN_org_x(ray, N, i), RTCRayN_org_y(ray, N, i), RTCRayN_org_z(ray, N, i));
        Vec3 d(RTCRayN_dir_x(ray, N, i), RTCRayN_dir_y(ray, N, i), RTCRayN_dir_z(ray, N, i));
        float &tfar = RTCRayN_tfar(ray, N, i);
        double t[2], uv[2][2];
        int n = s.kind == Shape::Bilinear ? patch_hits(patch_of(s, args->primID), o, d, RTCRayN_tnear(ray, N, i), tfar, t, uv)
                                          : quadric_hits(s, o, d, RTCRayN_tnear(ray, N, i), tfar, t);
        int k = first_visible(g, n, t, s.kind == Shape::Bilinear ? uv : nullptr, args->primID, o, d, tfar);
        if (k < 0) continue;
        if (occlusion) {
            tfar = -INFINITY;
            continue;
        }
        if constexpr (!occlusion) {
            RTCHitN *hit = RTCRayHitN_HitN(args->rayhit, args->N);
            tfar = (float)t[k];
            // (hit_of makes the normal the renderers use; Embree's is for its own use only)
            Vec3 n = s.kind == Shape::Bilinear ? Vec3(0, 0, 1) : quadric_normal(s, o + d * t[k]);
            RTCHitN_Ng_x(hit, N, i) = (float)n.x, RTCHitN_Ng_y(hit, N, i) = (float)n.y, RTCHitN_Ng_z(hit, N, i) = (float)n.z;
            RTCHitN_u(hit, N, i) = s.kind == Shape::Bilinear ? (float)uv[k][0] : 0.0f;
            RTCHitN_v(hit, N, i) = s.kind == Shape::Bilinear ? (float)uv[k][1] : 0.0f;
            RTCHitN_primID(hit, N, i) = args->primID;
            RTCHitN_geomID(hit, N, i) = args->geomID;
            RTCHitN_instID(hit, N, i, 0) = args->context->instID[0];
        }
    }
}

void patch_bounds(const RTCBoundsFunctionArguments *args)
{
    const GeometryData &g = *(const GeometryData *)args->geometryUserPtr;
    Patch q = patch_of(g.rt->scene().shapes[g.shape], args->primID);
    Vec3 lo = q.p00, hi = q.p00;
    for (Vec3 p : {q.p10, q.p01, q.p11})
        for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], p[a]), hi[a] = std::max(hi[a], p[a]);
    set_bounds(args->bounds_o, lo, hi);
}

// Embree's triangles and spheres with alpha: each candidate hit filtered by the alpha test.
void alpha_filter(const RTCFilterFunctionNArguments *args)
{
    const GeometryData &g = *(const GeometryData *)args->geometryUserPtr;
    const unsigned N = args->N;
    for (unsigned i = 0; i < N; ++i) {
        if (args->valid[i] != -1) continue;
        float o[3] = {RTCRayN_org_x(args->ray, N, i), RTCRayN_org_y(args->ray, N, i), RTCRayN_org_z(args->ray, N, i)};
        float d[3] = {RTCRayN_dir_x(args->ray, N, i), RTCRayN_dir_y(args->ray, N, i), RTCRayN_dir_z(args->ray, N, i)};
        float t = RTCRayN_tfar(args->ray, N, i);  // (the candidate's distance)
        Hit h;
        h.t = t, h.shape = g.shape, h.prim = RTCHitN_primID(args->hit, N, i);
        h.u = RTCHitN_u(args->hit, N, i), h.v = RTCHitN_v(args->hit, N, i);
        h.p = Vec3(o[0], o[1], o[2]) + Vec3(d[0], d[1], d[2]) * t;
        h.ng = g.rt->geometric_normal(h);
        if (!g.rt->alpha_passes(h, o, d)) args->valid[i] = 0;
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

RTCScene EmbreeScene::new_scene(bool robust)
{
    RTCScene sc = rtcNewScene(device_);
    if (!sc) {
        std::string why = errors_->text();
        throw SceneError(src_.source + ": Embree could not create a scene" + (why.empty() ? "" : ": " + why));
    }
    rtcSetSceneBuildQuality(sc, RTC_BUILD_QUALITY_HIGH);
    if (robust) rtcSetSceneFlags(sc, RTC_SCENE_FLAG_ROBUST);
    return sc;
}

RTCGeometry EmbreeScene::geometry(unsigned k)
{
    const Shape &s = src_.shapes[k];
    auto failed = [&](const char *doing) {
        std::string why = errors_->text();
        return SceneError(src_.source + ": Embree could not " + doing + (why.empty() ? "" : ": " + why));
    };
    // Embree's triangles (alpha: a filter function) and spheres; the rest user geometry (quadrics.h,
    // bilinear_patch.h)
    bool user = s.kind == Shape::Bilinear || (s.kind != Shape::Triangles && (s.kind != Shape::Sphere || s.ellipsoid || s.has_alpha()));
    RTCGeometry g = rtcNewGeometry(device_, s.kind == Shape::Triangles ? RTC_GEOMETRY_TYPE_TRIANGLE
                                            : user                        ? RTC_GEOMETRY_TYPE_USER
                                                                          : RTC_GEOMETRY_TYPE_SPHERE_POINT);
    if (!g) throw failed("create a geometry");
    void *data = &geometry_data_[k];
    bool filled = false;
    if (s.kind == Shape::Triangles) {
        size_t nv = s.P.size() / 3, nt = s.indices.size() / 3;
        float *v = (float *)rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), nv);
        unsigned *i = (unsigned *)rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                          3 * sizeof(unsigned), nt);
        if (v && i) {
            std::copy(s.P.begin(), s.P.end(), v);
            std::copy(s.indices.begin(), s.indices.end(), i);
            filled = true;
        }
        if (s.has_alpha()) {
            rtcSetGeometryUserData(g, data);
            rtcSetGeometryIntersectFilterFunction(g, alpha_filter);
            rtcSetGeometryOccludedFilterFunction(g, alpha_filter);
        }
    } else if (user) {
        rtcSetGeometryUserPrimitiveCount(g, (unsigned)s.primitive_count());
        rtcSetGeometryUserData(g, data);
        rtcSetGeometryBoundsFunction(g, s.kind == Shape::Bilinear ? patch_bounds : quadric_bounds, nullptr);
        rtcSetGeometryIntersectFunction(g, user_query<RTCIntersectFunctionNArguments>);
        rtcSetGeometryOccludedFunction(g, user_query<RTCOccludedFunctionNArguments>);
        filled = true;
    } else {
        float *v = (float *)rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, 4 * sizeof(float), 1);
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
    return g;
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
    scene_ = new_scene(robust);
    bool any_alpha = false;
    for (const Shape &s : scene.shapes) any_alpha = any_alpha || s.has_alpha();
    if (any_alpha) alpha_ = std::make_unique<AlphaTest>(scene);
    geometry_data_.clear();
    for (unsigned k = 0; k < scene.shapes.size(); ++k) geometry_data_.push_back({this, k});  // (the geometries point into it)
    objects_.assign(scene.objects.size(), nullptr);
    object_shapes_.resize(scene.objects.size());
    for (unsigned k = 0; k < scene.shapes.size(); ++k) {
        const Shape &s = scene.shapes[k];
        RTCScene target = scene_;
        std::vector<unsigned> *shape_of = &shape_of_geom_;
        if (s.object >= 0) {  // an object's shape: in the object's own scene, which its instances place
            if (!objects_[s.object]) objects_[s.object] = new_scene(robust);
            target = objects_[s.object], shape_of = &object_shapes_[s.object];
        }
        RTCGeometry g = geometry(k);
        unsigned id = rtcAttachGeometry(target, g);
        rtcReleaseGeometry(g);
        if (id == RTC_INVALID_GEOMETRY_ID) throw failed("attach a geometry");
        if (shape_of->size() <= id) shape_of->resize(id + 1);
        (*shape_of)[id] = k;
    }
    for (RTCScene o : objects_)
        if (o) rtcCommitScene(o);
    for (unsigned k = 0; k < scene.instances.size(); ++k) {  // Embree instances, their transforms in float
        const Instance &in = scene.instances[k];
        RTCGeometry g = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_INSTANCE);
        if (!g) throw failed("create an instance");
        rtcSetGeometryInstancedScene(g, objects_[in.object]);
        rtcSetGeometryTimeStepCount(g, 1);
        float xfm[12];  // 3x4, column major
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 3; ++r) xfm[3 * c + r] = (float)in.world_from_object.m[r][c];
        rtcSetGeometryTransform(g, 0, RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR, xfm);
        rtcCommitGeometry(g);
        unsigned id = rtcAttachGeometry(scene_, g);
        rtcReleaseGeometry(g);
        if (id == RTC_INVALID_GEOMETRY_ID) throw failed("attach an instance");
        if (shape_of_geom_.size() <= id) shape_of_geom_.resize(id + 1);
        if (instance_of_geom_.size() <= id) instance_of_geom_.resize(id + 1);
        shape_of_geom_[id] = ~0u, instance_of_geom_[id] = k;
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
    for (RTCScene &o : objects_)
        if (o) rtcReleaseScene(o), o = nullptr;
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
    *hit = hit_of(o, d, rh.ray.tfar, rh.hit.geomID, rh.hit.primID, rh.hit.u, rh.hit.v, rh.hit.instID[0]);
    return true;
}

Hit EmbreeScene::hit_of(Vec3 o, Vec3 d, float tfar, unsigned geom_id, unsigned prim_id, float u, float v,
                        unsigned inst_id) const
{
    Hit hit;
    hit.t = tfar;
    hit.prim = prim_id;
    hit.u = u;
    hit.v = v;
    hit.p = o + d * hit.t;  // (Embree's instances keep the ray's parameter t)
    if (inst_id != RTC_INVALID_GEOMETRY_ID) {
        hit.instance = &src_.instances[instance_of_geom_[inst_id]];
        hit.shape = object_shapes_[hit.instance->object][geom_id];
    } else {
        hit.shape = shape_of_geom_[geom_id];
    }
    hit.ng = geometric_normal(hit);
    if (hit.instance) hit.ng = normalize(world_normal(hit, hit.ng));  // by the inverse transpose, as pbrt-v4's instances
    return hit;
}

Vec3 EmbreeScene::geometric_normal(const Hit &h) const
{
    const Shape &s = src_.shapes[h.shape];
    if (s.kind == Shape::Triangles) return normals_[first_normal_[h.shape] + h.prim];
    if (s.kind == Shape::Bilinear) return patch_normal(s, h.prim, h.u, h.v);
    Vec3 n = quadric_normal(s, shape_point(h));
    return s.reverse_orientation ? -n : n;
}

bool EmbreeScene::alpha_passes(const Hit &h, const float o[3], const float d[3]) const
{
    return alpha_->passes(src_.shapes[h.shape], h, o, d);
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
