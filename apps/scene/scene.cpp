// scene.cpp - parameter lookups, bounds, the camera, and load_scene's dispatch.
#include "scene.h"

#include <cmath>
#include <cstdio>

#include "builtin.h"
#include "mesh_io.h"
#include "pbrt_parser.h"
#include "tabulated_bsdf.h"

#include <sys/stat.h>

#include <algorithm>
#include <cstring>
#include <limits>

namespace udm1scene {

const Param *ParamSet::find(const std::string &name) const
{
    for (int pass = 0; pass < 2; ++pass)  // the directive's own (the last given), then the latest Attribute's
        for (size_t i = params.size(); i-- > 0;)
            if (params[i].attribute == (pass == 1) && params[i].name == name) return &params[i];
    return nullptr;
}

const Param *ParamSet::find(const std::string &name, const char *type) const
{
    const Param *p = find(name);
    if (p && p->type != type)
        throw SceneError(p->where + ": '" + name + "' must be \"" + type + " " + name + "\", not \"" + p->type + " " + name +
                         "\"");
    return p;
}

double ParamSet::get_float(const std::string &name, double fallback) const
{
    const Param *p = find(name, "float");
    if (!p) return fallback;
    if (p->numbers.size() != 1) throw SceneError(p->where + ": '" + name + "' needs one number");
    return p->numbers[0];
}

int ParamSet::get_int(const std::string &name, int fallback) const
{
    const Param *p = find(name, "integer");
    if (!p) return fallback;
    if (p->numbers.size() != 1) throw SceneError(p->where + ": '" + name + "' needs one number");
    double v = p->numbers[0];
    if (!(v >= -2147483648.0 && v <= 2147483647.0) || v != std::floor(v))  // range first: the cast is UB outside
        throw SceneError(p->where + ": '" + name + "' needs a whole number between -2^31 and 2^31 - 1, not " +
                         number_text(v));
    return (int)v;
}

std::string number_text(double v)
{
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    return buf;
}

bool ParamSet::get_bool(const std::string &name, bool fallback) const
{
    const Param *p = find(name, "bool");
    if (!p) return fallback;
    if (p->strings.size() != 1 || (p->strings[0] != "true" && p->strings[0] != "false"))
        throw SceneError(p->where + ": '" + name + "' needs true or false");
    return p->strings[0] == "true";
}

std::string ParamSet::get_string(const std::string &name, const std::string &fallback) const
{
    const Param *p = find(name, "string");
    if (!p) return fallback;
    if (p->strings.size() != 1) throw SceneError(p->where + ": '" + name + "' needs one string");
    return p->strings[0];
}

bool ParamSet::get_rgb(const std::string &name, Vec3 *rgb) const
{
    const Param *p = find(name);
    if (!p) return false;
    if (p->type != "rgb" || p->numbers.size() != 3)
        throw SceneError(p->where + ": '" + name + "' needs an rgb value (3 numbers)");
    *rgb = Vec3(p->numbers[0], p->numbers[1], p->numbers[2]);
    return true;
}

Vec3 ParamSet::get_point(const std::string &name, Vec3 fallback) const
{
    const Param *p = find(name, "point3");
    if (!p) return fallback;
    if (p->numbers.size() != 3) throw SceneError(p->where + ": '" + name + "' needs a point (3 numbers)");
    return Vec3(p->numbers[0], p->numbers[1], p->numbers[2]);
}

size_t Scene::triangle_count() const
{
    size_t n = 0;
    std::vector<size_t> of_object(objects.size(), 0);
    for (const Shape &s : shapes)
        if (s.kind == Shape::Triangles) (s.object < 0 ? n : of_object[s.object]) += s.indices.size() / 3;
    for (const Instance &i : instances) n += of_object[i.object];
    return n;
}

void Scene::bounds(Vec3 *lo, Vec3 *hi) const
{
    const double inf = std::numeric_limits<double>::infinity();
    *lo = Vec3(inf, inf, inf);
    *hi = Vec3(-inf, -inf, -inf);
    auto grow = [&](Vec3 p, double r) {
        for (int a = 0; a < 3; ++a) {
            (*lo)[a] = std::min((*lo)[a], p[a] - r);
            (*hi)[a] = std::max((*hi)[a], p[a] + r);
        }
    };
    std::vector<Vec3> object_lo(objects.size(), Vec3(inf, inf, inf)), object_hi(objects.size(), Vec3(-inf, -inf, -inf));
    for (const Shape &s : shapes) {
        if (s.object < 0) {
            if (s.kind == Shape::Sphere && !s.ellipsoid) grow(s.center, s.radius);
            if ((s.kind == Shape::Sphere && s.ellipsoid) || s.kind == Shape::Disk || s.kind == Shape::Cylinder) {
                Vec3 a, b;
                shape_bounds(s, &a, &b);
                grow(a, 0), grow(b, 0);
            }
            for (size_t i = 0; i + 2 < s.P.size(); i += 3) grow(Vec3(s.P[i], s.P[i + 1], s.P[i + 2]), 0);
            continue;
        }
        Vec3 &a = object_lo[s.object], &b = object_hi[s.object];  // an object's shape: the object's box
        auto add = [&](Vec3 p, double r) {
            for (int k = 0; k < 3; ++k) a[k] = std::min(a[k], p[k] - r), b[k] = std::max(b[k], p[k] + r);
        };
        if (s.kind == Shape::Sphere && !s.ellipsoid) add(s.center, s.radius);
        if ((s.kind == Shape::Sphere && s.ellipsoid) || s.kind == Shape::Disk || s.kind == Shape::Cylinder) {
            Vec3 c, d;
            shape_bounds(s, &c, &d);
            add(c, 0), add(d, 0);
        }
        for (size_t i = 0; i + 2 < s.P.size(); i += 3) add(Vec3(s.P[i], s.P[i + 1], s.P[i + 2]), 0);
    }
    for (const Instance &in : instances) {  // the corners of the object's box, placed
        const Vec3 &a = object_lo[in.object], &b = object_hi[in.object];
        if (!(a.x <= b.x)) continue;  // an empty object
        for (int c = 0; c < 8; ++c) grow(in.world_from_object.point(Vec3(c & 1 ? b.x : a.x, c & 2 ? b.y : a.y, c & 4 ? b.z : a.z)), 0);
    }
}

void Scene::film_window(int w, int h, int window[4]) const
{
    int x0 = 0, y0 = 0, x1 = w, y1 = h;
    if (has_crop) {  // pbrt-v4: ceil(resolution * fraction), in float
        x0 = (int)std::ceil((float)w * crop[0]), x1 = (int)std::ceil((float)w * crop[1]);
        y0 = (int)std::ceil((float)h * crop[2]), y1 = (int)std::ceil((float)h * crop[3]);
    } else if (has_pixel_bounds) {
        x0 = std::max(0, pixel_bounds[0]), x1 = std::min(w, pixel_bounds[1]);
        y0 = std::max(0, pixel_bounds[2]), y1 = std::min(h, pixel_bounds[3]);
    }
    if (!(x0 < x1 && y0 < y1))
        throw SceneError(source + ": the Film's " + (has_crop ? "cropwindow" : "pixelbounds") + " leaves no pixel of the " +
                         std::to_string(w) + "x" + std::to_string(h) + " film");
    window[0] = x0, window[1] = y0, window[2] = x1, window[3] = y1;
}

std::string resolve_path(const std::string &search_dir, const std::string &name)
{
    if (search_dir.empty() || name.empty() || name[0] == '/') return name;
    std::string p = search_dir + (search_dir.back() == '/' ? "" : "/") + name;
    struct stat st;
    return stat(p.c_str(), &st) == 0 ? p : name;
}

namespace {
struct Fnv1a {
    uint64_t h = 0xcbf29ce484222325ull;
    void bytes(const void *p, size_t n)
    {
        for (size_t i = 0; i < n; ++i) h = (h ^ ((const unsigned char *)p)[i]) * 0x100000001b3ull;
    }
    template <class T> void value(T v) { bytes(&v, sizeof v); }
    template <class T> void vec(const std::vector<T> &v)
    {
        value((uint64_t)v.size());
        if (!v.empty()) bytes(v.data(), v.size() * sizeof(T));
    }
};
}  // namespace

namespace {
// Whether sphere s's object space is the world's axes about its centre (moved and uniformly scaled only).
bool object_frame_is_world(const Shape &s)
{
    const Mat4 &m = s.world_from_object;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            if (m.m[i][j] != (i == j ? m.m[0][0] : 0.0)) return false;
    return m.m[0][0] > 0;
}
}  // namespace

bool make_sphere(const Mat4 &world_from_object, double r, Shape *s)
{
    Mat4 inverse;
    if (!world_from_object.affine() || !world_from_object.inverse(&inverse) || !(r > 0)) return false;
    s->kind = Shape::Sphere;
    s->world_from_object = world_from_object, s->object_from_world = inverse;
    s->object_radius = r;
    s->center = world_from_object.point(Vec3(0, 0, 0));
    double scale;
    s->ellipsoid = !world_from_object.similarity(1e-9, &scale);
    s->radius = s->ellipsoid ? 0 : r * world_from_object.scale_factor();
    return true;
}

Vec3 sphere_object_point(const Shape &s, Vec3 p) { return s.object_from_world.point(p); }

Vec3 sphere_normal(const Shape &s, Vec3 p)
{
    if (!s.ellipsoid) return normalize(p - s.center);
    Vec3 q = sphere_object_point(s, p);
    const Mat4 &inv = s.object_from_world;  // by the inverse transpose
    return normalize(Vec3(inv.m[0][0] * q.x + inv.m[1][0] * q.y + inv.m[2][0] * q.z,
                          inv.m[0][1] * q.x + inv.m[1][1] * q.y + inv.m[2][1] * q.z,
                          inv.m[0][2] * q.x + inv.m[1][2] * q.y + inv.m[2][2] * q.z));
}

void sphere_bounds(const Shape &s, Vec3 *lo, Vec3 *hi)
{
    // the image of the ball: along world axis i it reaches r times the length of row i of the 3x3 part
    const Mat4 &m = s.world_from_object;
    for (int i = 0; i < 3; ++i) {
        double e = s.object_radius * std::sqrt(m.m[i][0] * m.m[i][0] + m.m[i][1] * m.m[i][1] + m.m[i][2] * m.m[i][2]);
        (*lo)[i] = s.center[i] - e, (*hi)[i] = s.center[i] + e;
    }
}

bool make_quadric(const Mat4 &world_from_object, Shape *s)
{
    Mat4 inverse;
    if (!world_from_object.affine() || !world_from_object.inverse(&inverse)) return false;
    s->world_from_object = world_from_object, s->object_from_world = inverse;
    s->center = world_from_object.point(Vec3(0, 0, 0));
    return true;
}

void shape_bounds(const Shape &s, Vec3 *lo, Vec3 *hi)
{
    const double inf = std::numeric_limits<double>::infinity();
    *lo = Vec3(inf, inf, inf), *hi = Vec3(-inf, -inf, -inf);
    if (s.kind == Shape::Sphere) return sphere_bounds(s, lo, hi);
    if (s.kind == Shape::Disk || s.kind == Shape::Cylinder) {  // the object-space box's corners
        double r = s.object_radius, z0 = s.kind == Shape::Disk ? s.height : s.zmin, z1 = s.kind == Shape::Disk ? s.height : s.zmax;
        for (int c = 0; c < 8; ++c) {
            Vec3 p = s.world_from_object.point(Vec3(c & 1 ? r : -r, c & 2 ? r : -r, c & 4 ? z1 : z0));
            for (int a = 0; a < 3; ++a) (*lo)[a] = std::min((*lo)[a], p[a]), (*hi)[a] = std::max((*hi)[a], p[a]);
        }
        return;
    }
    for (size_t i = 0; i + 2 < s.P.size(); i += 3)
        for (int a = 0; a < 3; ++a) (*lo)[a] = std::min<double>((*lo)[a], s.P[i + a]), (*hi)[a] = std::max<double>((*hi)[a], s.P[i + a]);
}

uint64_t Scene::digest() const
{
    Fnv1a f;
    f.value(width), f.value(height);
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) f.value(camera.world_from_camera.m[r][c]);
    f.value(camera.fov), f.value(camera.lens_radius), f.value(camera.focal_distance);
    // (what older scenes do not have is hashed only where a scene has it, so that their digests stay)
    if (has_crop || has_pixel_bounds || max_component != HUGE_VAL || film_scale != 1) {
        f.value(has_crop), f.value(has_pixel_bounds), f.value(max_component), f.value(film_scale);
        for (int k = 0; k < 4; ++k) f.value(crop[k]), f.value(pixel_bounds[k]);
    }
    if (white_balance != 0) f.value(white_balance);
    if (!pixel_filter.unit_box()) {
        const PixelFilter &pf = pixel_filter;
        for (char ch : pf.type) f.value(ch);
        f.value(pf.xradius), f.value(pf.yradius), f.value(pf.sigma), f.value(pf.b), f.value(pf.c), f.value(pf.tau);
    }
    f.value((uint64_t)shapes.size());
    for (const Shape &s : shapes) {
        f.value((int)s.kind), f.vec(s.P), f.vec(s.N), f.vec(s.indices);
        if (s.object >= 0) f.value(s.object);
        f.value(s.center.x), f.value(s.center.y), f.value(s.center.z), f.value(s.radius);
        f.value(s.material), f.value(s.light), f.value(s.reverse_orientation);
        if (!media.empty()) f.value(s.inside), f.value(s.outside);  // (scenes without media keep their digests)
        if ((s.kind == Shape::Sphere && (s.ellipsoid || !object_frame_is_world(s))) || s.kind == Shape::Disk ||
            s.kind == Shape::Cylinder)  // (its texture coordinates; the other quadrics' placement)
            for (int r = 0; r < 4; ++r)
                for (int c = 0; c < 4; ++c) f.value(s.world_from_object.m[r][c]);
        if (s.kind == Shape::Disk || s.kind == Shape::Cylinder)
            f.value(s.object_radius), f.value(s.inner_radius), f.value(s.height), f.value(s.zmin), f.value(s.zmax),
                f.value(s.phi_max);
        if (!s.UV.empty()) f.vec(s.UV);  // (texture coordinates change textured images)
        if (s.has_alpha()) f.value(s.alpha), f.value(s.alpha_tex);
    }
    for (const Material &m : materials) {
        f.vec(std::vector<char>(m.type.begin(), m.type.end()));
        for (const Param &p : m.params.params) {
            f.vec(std::vector<char>(p.name.begin(), p.name.end())), f.vec(p.numbers);
            for (const std::string &t : p.strings) f.vec(std::vector<char>(t.begin(), t.end()));
        }
        if (m.tabulated) f.value(m.tabulated->digest);  // (the file's contents, not only its name)
    }
    for (const Texture &t : textures) {
        for (const std::string *x : {&t.name, &t.kind, &t.type, &t.filename, &t.wrap})
            f.vec(std::vector<char>(x->begin(), x->end()));
        f.value(t.srgb), f.value(t.invert), f.value(t.point), f.value(t.scale);
        for (const TextureInput *in : {&t.tex1, &t.tex2, &t.amount})
            f.value(in->tex), f.value(in->value), f.value(in->rgb.x), f.value(in->rgb.y), f.value(in->rgb.z);
        f.value(t.dir.x), f.value(t.dir.y), f.value(t.dir.z), f.value(t.dimension);
        const TextureMapping &m = t.mapping;
        f.value((int)m.kind), f.value(m.su), f.value(m.sv), f.value(m.du), f.value(m.dv);
        f.value(m.v1.x), f.value(m.v1.y), f.value(m.v1.z), f.value(m.v2.x), f.value(m.v2.y), f.value(m.v2.z);
        for (int r = 0; r < 4; ++r)
            for (int c = 0; c < 4; ++c) f.value(m.texture_from_world.m[r][c]);
    }
    if (!media.empty()) f.value(camera.medium), f.vec(std::vector<char>(integrator.begin(), integrator.end()));
    for (const Medium &m : media)
        for (double x : {m.sigma_a.x, m.sigma_a.y, m.sigma_a.z, m.sigma_s.x, m.sigma_s.y, m.sigma_s.z, m.Le.x, m.Le.y, m.Le.z, m.g})
            f.value(x);
    if (!instances.empty()) f.value((uint64_t)instances.size());
    for (const Instance &in : instances) {
        f.value(in.object);
        for (int r = 0; r < 4; ++r)
            for (int c = 0; c < 4; ++c) f.value(in.world_from_object.m[r][c]);
    }
    for (const AreaLight &l : lights) f.value(l.L.x), f.value(l.L.y), f.value(l.L.z), f.value(l.scale), f.value(l.twosided);
    for (const LightSource &l : light_sources) {
        f.value((int)l.kind), f.value(l.L.x), f.value(l.L.y), f.value(l.L.z), f.value(l.position.x), f.value(l.position.y),
            f.value(l.position.z), f.value(l.direction.x), f.value(l.direction.y), f.value(l.direction.z);
        f.value(l.cos_start), f.value(l.cos_end), f.value(l.illuminance);
        for (int r = 0; r < 4; ++r)
            for (int c = 0; c < 4; ++c) f.value(l.world_from_light.m[r][c]);
        f.vec(std::vector<char>(l.filename.begin(), l.filename.end()));
    }
    return f.h;
}

Vec3 triangle_normal(const Shape &s, unsigned prim)
{
    const uint32_t *i = &s.indices[3 * (size_t)prim];
    auto P = [&](uint32_t k) { return Vec3(s.P[3 * k], s.P[3 * k + 1], s.P[3 * k + 2]); };
    Vec3 n = normalize(cross(P(i[0]) - P(i[2]), P(i[1]) - P(i[2])));
    if (!s.N.empty()) {
        auto N = [&](uint32_t k) { return Vec3(s.N[3 * k], s.N[3 * k + 1], s.N[3 * k + 2]); };
        if (dot(n, N(i[0]) + N(i[1]) + N(i[2])) < 0) n = -n;
    } else if (s.reverse_orientation) {
        n = -n;
    }
    return n;
}

CameraRays::CameraRays(const Scene &s) : world_from_camera_(s.camera.world_from_camera)
{
    // pbrt's perspective camera: the screen window spans [-1, 1] along the shorter axis
    double aspect = (double)s.width / s.height;
    double sx0 = aspect > 1 ? -aspect : -1, sx1 = -sx0, sy0 = aspect > 1 ? -1 : -1 / aspect, sy1 = -sy0;
    w_ = s.width, h_ = s.height;  // divided by (not multiplied by the inverse): the rays keep their bits
    sx0_ = sx0, sx_span_ = sx1 - sx0, sy1_ = sy1, sy_span_ = sy1 - sy0;
    tan_half_fov_ = std::tan(s.camera.fov * 3.14159265358979323846 / 360.0);
    origin_ = world_from_camera_.point(Vec3(0, 0, 0));
    lens_radius_ = s.camera.lens_radius, focal_distance_ = s.camera.focal_distance;
}

void CameraRays::ray(double px, double py, double lu, double lv, Vec3 *origin, Vec3 *dir) const
{
    if (!(lens_radius_ > 0)) return ray(px, py, origin, dir);
    double sx = sx0_ + (px / w_) * sx_span_;
    double sy = sy1_ - (py / h_) * sy_span_;
    Vec3 d = normalize(Vec3(sx * tan_half_fov_, sy * tan_half_fov_, 1.0));
    // Shirley and Chiu's concentric map of (lu, lv) to the unit disk, as pbrt's SampleUniformDiskConcentric
    double ox = 2 * lu - 1, oy = 2 * lv - 1, r, theta;
    if (ox == 0 && oy == 0) {
        r = 0, theta = 0;
    } else if (std::fabs(ox) > std::fabs(oy)) {
        r = ox, theta = 0.78539816339744830962 * (oy / ox);
    } else {
        r = oy, theta = 1.57079632679489661923 - 0.78539816339744830962 * (ox / oy);
    }
    Vec3 lens(lens_radius_ * r * std::cos(theta), lens_radius_ * r * std::sin(theta), 0);
    Vec3 focus = d * (focal_distance_ / d.z);  // where the pinhole ray meets the plane of focus
    *origin = world_from_camera_.point(lens);
    *dir = normalize(world_from_camera_.vector(normalize(focus - lens)));
}

void CameraRays::ray(double px, double py, Vec3 *origin, Vec3 *dir) const
{
    double sx = sx0_ + (px / w_) * sx_span_;
    double sy = sy1_ - (py / h_) * sy_span_;
    Vec3 d = normalize(Vec3(sx * tan_half_fov_, sy * tan_half_fov_, 1.0));
    *origin = origin_;
    *dir = normalize(world_from_camera_.vector(d));
}

void CameraRays::pinhole(Vec3 *origin, Vec3 *a, Vec3 *b, Vec3 *c) const
{
    // camera space (sx tan, sy tan, 1) with sx = sx0 + px (span / w), sy = sy1 - py (span / h): linear in px, py
    Vec3 mx = world_from_camera_.vector(Vec3(1, 0, 0)), my = world_from_camera_.vector(Vec3(0, 1, 0));
    Vec3 mz = world_from_camera_.vector(Vec3(0, 0, 1));
    *origin = origin_;
    *a = mz + mx * (sx0_ * tan_half_fov_) + my * (sy1_ * tan_half_fov_);
    *b = mx * (sx_span_ / w_ * tan_half_fov_);
    *c = my * (-sy_span_ / h_ * tan_half_fov_);
}

void camera_ray(const Scene &s, double px, double py, Vec3 *origin, Vec3 *dir) { CameraRays(s).ray(px, py, origin, dir); }

Scene load_scene(const std::string &path, Need need)
{
    if (path.rfind("builtin:", 0) == 0) return builtin_scene(path.substr(8));
    auto ends = [&](const char *ext) {
        size_t n = std::strlen(ext);
        if (path.size() < n) return false;
        std::string tail = path.substr(path.size() - n);
        std::transform(tail.begin(), tail.end(), tail.begin(), ::tolower);
        return tail == ext;
    };
    if (ends(".pbrt") || ends(".pbrt.gz")) return parse_pbrt(path, need);
    if (ends(".ply") || ends(".ply.gz") || ends(".obj")) return mesh_scene(path);
    throw SceneError(path + ": not a .pbrt, .pbrt.gz, .ply, .ply.gz or .obj file, nor builtin:NAME");
}

}  // namespace udm1scene
