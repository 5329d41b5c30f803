// embree_scene.h - a Scene on Embree 3: one device, one committed scene of
// triangle meshes and spheres (as Embree sphere points; as user geometry intersected in object space
// where a transform makes them ellipsoids), each triangle's geometric
// normal (computed once), and the queries the renderers need. Const methods are
// safe from any number of threads.
#pragma once

#include "scene.h"

#include <embree3/rtcore.h>

#include <memory>
#include <mutex>
#include <string>

namespace udm1scene {

// How far rays leaving p start from it: 2^-18 (64 float ulps) of the largest magnitude among p's coordinates and the
// distance t the ray that found p travelled (float intersection errors scale with both), never less
// than 2^-40. Relative to the point, not the scene: a point near the origin of a 1e5-wide floor still
// starts its rays a few ulps off the surface, not one unit off it.
double ray_offset(Vec3 p, double t = 0);

// A shadow ray: the open segment between a surface point p (unit geometric normal n, found by a ray of
// length t) and a point q on a light (unit normal nq; a zero vector for a point with no surface). It
// leaves p offset to the side of its surface that q is on and ends at q offset to the side of the
// light's surface that the origin is on, so that it stops short of both surfaces at any angle, at any
// length and anywhere in space (pbrt-v4's SpawnRayTo). A ray towards the sky or a distant light:
// segment_to_infinity.
struct Segment {
    Vec3 o, d;   // origin and unit direction
    double len;  // tfar (0 when the two offset points coincide: nothing to test)
};
Segment shadow_segment(Vec3 p, Vec3 n, double t, Vec3 q, Vec3 nq);
Segment segment_to_infinity(Vec3 p, Vec3 n, double t, Vec3 w);

struct Hit {
    double t = 0;
    unsigned shape = 0, prim = 0;  // index into Scene::shapes, triangle index
    Vec3 p, ng;                    // position, unit geometric normal (as the geometry faces it)
    double u = 0, v = 0;           // barycentrics
};

// One query as Embree received it (for the replay benchmark, bench/bench_pt_embree.cpp).
struct RayQuery {
    float org[3], dir[3], tnear, tfar;
    bool shadow;  // occluded() rather than intersect()
};

// What Embree reported through its device's error function (from any thread), for the tool's one-line
// error: Embree itself prints nothing (its device is made with verbose=0).
class EmbreeErrors {
public:
    // Install on `device` (the object must outlive it).
    void attach(RTCDevice device);
    // "" if no error was reported, else the first one as one line: its code's name and Embree's message,
    // and how many more followed.
    std::string text() const;

private:
    static void record(void *self, RTCError code, const char *message);
    mutable std::mutex mutex_;
    std::string first_;
    unsigned count_ = 0;
};

// An Embree error code's name ("RTC_ERROR_OUT_OF_MEMORY").
const char *embree_error_name(RTCError code);

class EmbreeScene {
public:
    // robust: Embree's robust traversal (RTC_SCENE_FLAG_ROBUST). Without it rays through shared edges
    // of axis-aligned faces leak out of closed boxes at most scales (tests/cpp/test_ao.cpp); it costs
    // speed (BENCHMARKS.md). Throws SceneError "SCENE: Embree ...: <its message>" if Embree fails.
    explicit EmbreeScene(const Scene &scene, bool robust = true);
    ~EmbreeScene();
    EmbreeScene(const EmbreeScene &) = delete;
    EmbreeScene &operator=(const EmbreeScene &) = delete;

    bool intersect(Vec3 o, Vec3 d, double tnear, double tfar, Hit *hit) const;
    bool occluded(Vec3 o, Vec3 d, double tnear, double tfar) const;
    // The hit that Embree reported for the ray o + t d (given to it in float) as intersect() makes it: for
    // loops that hand Embree many rays at once (rtcIntersectNp) and must find what intersect() finds.
    Hit hit_of(Vec3 o, Vec3 d, float tfar, unsigned geom_id, unsigned prim_id, float u, float v) const;
    // The origin for rays leaving hit h on side n (the side `incoming` came from): offset along n and
    // back along the incoming ray, so that a hit on an edge or in a concave corner starts strictly on
    // the visible side of both faces (offsetting along n alone leaves it on the other face's plane).
    Vec3 spawn_origin(const Hit &h, Vec3 incoming, Vec3 n) const { return h.p + (n - incoming) * ray_offset(h.p, h.t); }
    RTCScene handle() const { return scene_; }
    unsigned shape_of_geometry(unsigned geom_id) const { return shape_of_geom_[geom_id]; }  // Scene::shapes index
    unsigned geometry_count() const { return (unsigned)shape_of_geom_.size(); }              // IDs 0 .. count - 1
    // Benchmarks only: append every later query to *log (nullptr: stop). Not thread-safe: record with
    // one thread. The renderers never set it (one predictable branch per query).
    void record_queries(std::vector<RayQuery> *log) { log_ = log; }
    double scale() const { return scale_; }  // the scene's extent
    // Throws SceneError "SCENE: Embree failed while <doing>: ..." if Embree reported an error since the
    // scene was built (a query that Embree refused): the renderers call it after rendering.
    void check(const char *doing) const;

private:
    void build(const Scene &scene, bool robust);
    void release();

    const Scene &src_;
    std::unique_ptr<EmbreeErrors> errors_ = std::make_unique<EmbreeErrors>();
    RTCDevice device_ = nullptr;
    RTCScene scene_ = nullptr;
    std::vector<unsigned> shape_of_geom_;
    std::vector<size_t> first_normal_;  // per shape: its first triangle's entry in normals_
    std::vector<Vec3> normals_;         // triangle_normal() of every triangle, in shape order
    double scale_ = 1;
    std::vector<RayQuery> *log_ = nullptr;
};

}  // namespace udm1scene
