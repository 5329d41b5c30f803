// scene.h - a scene as udm1's renderers need it: triangle meshes and spheres
// in world space, materials and area lights as their parameters, a camera and
// a film. Loaded from the subset of the pbrt-v4 format that the target scenes
// use (pbrt_parser.h), from PLY and OBJ meshes, or built in (builtin.h).
#pragma once

#include "math.h"
#include "nanovdb_grid.h"
#include "pixel_filter.h"

#include <cmath>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace udm1scene {

// A scene error: "file:line: message" (or "file: message"), one line.
struct SceneError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// A number as a one-line error message shows it (any double, NaN and huge values included; never a
// cast to an integer type, which is undefined for values out of its range).
std::string number_text(double v);

// One parameter of a pbrt directive: "type name" [values].
struct Param {
    std::string type, name;
    std::vector<double> numbers;
    std::vector<std::string> strings;  // string, bool (as "true"/"false"), texture, spectrum names
    std::string where;                 // "file:line"
    bool attribute = false;            // a default from an Attribute directive, not the directive's own
};

// Its getters read a parameter of one type ("float", "integer", "bool", "string", "point3": pbrt-v4's for
// it) and refuse it given as another: pbrt-v4 looks parameters up by type and name, and refuses one it did
// not use. As in pbrt-v4, the directive's own parameters come first (the last of a name given twice), then
// the defaults of the Attribute directives in force (the latest first).
struct ParamSet {
    std::vector<Param> params;
    std::string where;  // the directive's "file:line"
    const Param *find(const std::string &name) const;
    const Param *find(const std::string &name, const char *type) const;  // refused if given as another type
    double get_float(const std::string &name, double fallback) const;
    int get_int(const std::string &name, int fallback) const;
    bool get_bool(const std::string &name, bool fallback) const;
    std::string get_string(const std::string &name, const std::string &fallback) const;
    bool get_rgb(const std::string &name, Vec3 *rgb) const;
    Vec3 get_point(const std::string &name, Vec3 fallback) const;  // "point3 name" [x y z]
};

// A texture-valued parameter of a texture: another texture (Scene::textures index), or a constant (a
// float, or an RGB triple for a spectrum texture: an albedo, as pbrt-v4 reads texture constants).
struct TextureInput {
    int tex = -1;
    double value = 0;
    Vec3 rgb;
};

// pbrt-v4's 2D texture mappings: (u, v) scaled and offset ("uv": s = uscale u + udelta, t = vscale v +
// vdelta), or from the point in the texture's space (texture_from_world, the inverse of the transform at
// its Texture directive): "spherical" (s = theta / pi, t = phi / 2 pi), "cylindrical" (s = (pi + phi) /
// 2 pi, t = z), "planar" (s = udelta + p . v1, t = vdelta + p . v2).
struct TextureMapping {
    enum Kind { UV, Spherical, Cylindrical, Planar } kind = UV;
    double su = 1, sv = 1, du = 0, dv = 0;
    Vec3 v1{1, 0, 0}, v2{0, 1, 0};
    Mat4 texture_from_world;
};

// A pbrt-v4 texture of the subset (Textures, textures.h, evaluates them):
//   "imagemap"     an image file (8-bit files decoded from sRGB unless "encoding" says linear), repeated,
//                  bilinear or point-sampled at the finest level, through its mapping; "maxanisotropy"
//                  is read and has no effect (it shapes pbrt-v4's footprint filter; udm1-pt samples the
//                  finest level)
//   "constant"     tex1: "value"
//   "scale"        tex1 ("tex") times tex2 ("scale", a float texture)
//   "mix"          (1 - amount) tex1 + amount tex2
//   "directionmix" a tex1 + (1 - a) tex2, a = |n . dir| (n the geometric normal, dir in world space)
//   "checkerboard" tex1 and tex2 in alternate squares of (s, t) through its mapping (dimension 2), or in
//                  alternate cubes of the point in texture space (dimension 3)
//   "fbm", "wrinkled", "windy" (float textures): pbrt-v4's solid noise sums (pbrt_noise.h) at the point in
//                  texture space (texture_from_world): FBm and Turbulence of `octaves` octaves with weight
//                  `omega` ("roughness"), and Windy
struct Texture {
    std::string name, kind, type;  // kind "float" or "spectrum"
    std::string filename;          // imagemap: resolved against the main scene file's folder (resolve_path)
    bool srgb = true, invert = false;
    bool point = false;            // imagemap: "filter" "point" (the nearest texel), else bilinear
    std::string wrap = "repeat";   // imagemap: "repeat", "clamp" or "black"
    double scale = 1;              // imagemap "scale"
    TextureInput tex1, tex2, amount;
    Vec3 dir{0, 1, 0};             // directionmix: unit, world space
    int dimension = 2;             // checkerboard
    int octaves = 8;               // fbm, wrinkled
    double omega = 0.5;            // fbm, wrinkled: "roughness", each octave's weight over the one before
    TextureMapping mapping;        // imagemap, checkerboard (dimension 2: its mapping; 3: texture_from_world), the noises
    std::string where;
};

struct TabulatedBsdf;  // tabulated_bsdf.h

struct Material {
    std::string name;  // MakeNamedMaterial's name ("" for Material)
    std::string type;  // "diffuse", "coateddiffuse", ...
    ParamSet params;
    std::shared_ptr<const TabulatedBsdf> tabulated;  // "measured": its file, read (one per file, shared)
};

// A pbrt-v4 medium in linear sRGB (the parser reduces its spectra, pbrt_parser.h): absorption and scattering
// coefficients per unit length with "scale" applied, the Henyey-Greenstein asymmetry g (clamped to
// [-0.99, 0.99] where it is evaluated, as pbrt-v4 clamps it), the emitted radiance Le with "Lescale" applied
// (a medium emits sigma_a Le per unit length). Of three kinds:
//   Homogeneous  sigma_a, sigma_s and Le everywhere.
//   UniformGrid  pbrt-v4's "uniformgrid": sigma_a and sigma_s times the density at the point, the nx x ny x nz
//                samples of `density` (x fastest) at the centres of the cells of the box [p0, p1] of the
//                medium's space, trilinear between them and falling to 0 across the outer half cells (pbrt-v4's
//                SampledGrid); 0 outside the box. Emission: Le (already normalized to luminance 1, as pbrt-v4
//                normalizes it) times the grid le_scale (one value: everywhere), or, with a temperature grid,
//                le_scale times the RGB of pbrt-v4's blackbody (normalized to 1 at its peak) at the temperature
//                (t - temperature_offset) * temperature_scale, none at or below 100 K.
//   Cloud        pbrt-v4's procedural "cloud": sigma_a and sigma_s times a density in [0, 1] made of pbrt-v4's
//                noise (pbrt_noise.h; cloud_density, wispiness, frequency) in the box [p0, p1]; no emission.
//   NanoVDB      pbrt-v4's "nanovdb": sigma_a and sigma_s times the trilinear density of the file's float grid
//                `vdb_density` (nanovdb_grid.h) at the point of the medium's space; [p0, p1] the box of the
//                grid's active voxels (with the temperature grid's, if any). Emission where the file has a
//                temperature grid and le_scale (one value) > 0: le_scale times the RGB of pbrt-v4's blackbody at
//                (t - temperature_offset) * temperature_scale, none at or below 100 K, as for a uniform grid.
// A grid medium is placed by medium_from_world, the inverse of the transform at its MakeNamedMedium.
struct Medium {
    enum Kind { Homogeneous, UniformGrid, Cloud, NanoVDB } kind = Homogeneous;
    std::string name;
    Vec3 sigma_a, sigma_s, Le;
    double g = 0;
    std::string where;  // its MakeNamedMedium's file:line
    // the grid media's
    Mat4 medium_from_world;
    Vec3 p0{0, 0, 0}, p1{1, 1, 1};
    int nx = 1, ny = 1, nz = 1;
    std::vector<float> density, le_scale{1.0f}, temperature;  // le_scale: 1 value or nx ny nz; temperature: none or nx ny nz
    double temperature_offset = 0, temperature_scale = 1;
    double cloud_density = 1, wispiness = 1, frequency = 5;
    std::shared_ptr<const NanoVdbGrid> vdb_density, vdb_temperature;  // the nanovdb medium's grids
    // Whether it may glow (the rendering adds its emission).
    bool emissive() const
    {
        if (kind == Cloud) return false;
        if (kind == UniformGrid && !temperature.empty()) return true;
        if (kind == NanoVDB) return vdb_temperature && le_scale[0] > 0;
        return Le.x > 0 || Le.y > 0 || Le.z > 0;
    }
};

struct AreaLight {
    Vec3 L{1, 1, 1};
    double scale = 1;
    bool twosided = false;
    std::string where;
};

// A pbrt-v4 LightSource: a light that is not a shape. Emission in linear sRGB with pbrt-v4's
// normalization and "scale", "power" or "illuminance" applied (radiance for distant and infinite
// lights, intensity for point and spot lights).
struct LightSource {
    enum Kind { Point, Spot, Distant, Infinite } kind = Point;
    Vec3 L{1, 1, 1};
    Vec3 position;                    // point, spot: world space
    Vec3 direction{0, 0, 1};          // spot: its axis; distant: towards the light (unit, world space)
    double cos_start = 1, cos_end = 0;  // spot: full intensity inside cos_start, none outside cos_end
    Mat4 world_from_light;            // infinite: the map's orientation (+z its pole)
    std::string filename;             // infinite: an equal-area octahedral environment map ("" uniform)
    double illuminance = -1;          // infinite with a map: the upper hemisphere's target illuminance
    std::string where;
};

// A triangle mesh, a mesh of bilinear patches, or one of pbrt-v4's quadrics placed by an affine
// world_from_object: the sphere of radius object_radius about the origin of its object space, the disk of
// radii (inner_radius, object_radius] at z = height, the cylinder of radius object_radius from zmin to
// zmax, the last two swept over phi in [0, phi_max]. Where the transform is a similarity (a rotation and
// a uniform scale, maybe mirrored) a sphere is a sphere in world space too, of centre `center` and radius
// `radius`, and is intersected as one; otherwise (`ellipsoid`), and for disks and cylinders always, the
// quadric is intersected in object space. Normals are the object-space normals by the inverse transpose
// and texture coordinates pbrt-v4's, from the object-space point (make_sphere and make_quadric set this up).
// A bilinear patch is pbrt-v4's: four vertices p00 p10 p01 p11 (`indices`, 4 per patch), the points
// (1-u)(1-v) p00 + u(1-v) p10 + (1-u)v p01 + uv p11, met exactly (not as two triangles).
struct Shape {
    enum Kind { Triangles, Sphere, Disk, Cylinder, Bilinear } kind = Triangles;
    std::vector<float> P;            // xyz per vertex, world space
    std::vector<float> N;            // optional per-vertex normals, world space
    std::vector<float> UV;           // optional
    std::vector<uint32_t> indices;   // 3 per triangle, 4 per bilinear patch
    Vec3 center;                     // sphere: world space
    double radius = 0;               // sphere: world space, if not an ellipsoid
    double object_radius = 0;        // quadrics: in object space
    double inner_radius = 0, height = 0;  // disk
    double zmin = 0, zmax = 0;            // cylinder
    double phi_max = 6.283185307179586;   // disk, cylinder: radians
    Mat4 world_from_object, object_from_world;  // quadrics
    bool ellipsoid = false;          // sphere: world_from_object is not a similarity
    int material = -1;               // index into Scene::materials
    int light = -1;                  // index into Scene::lights (an emitter), or -1
    bool reverse_orientation = false;
    // pbrt-v4's alpha: the shape is not there where alpha is 0, there with probability alpha between 0 and
    // 1 (a hash of the ray against it), a constant or a float texture (alpha_tex, Scene::textures index)
    double alpha = 1;
    int alpha_tex = -1;
    int inside = -1, outside = -1;   // its MediumInterface: Scene::media indices, -1 for none (vacuum)
    int object = -1;                 // the Scene::objects index of the ObjectBegin block that holds it (its
                                     // data then in the object's space, placed by Scene::instances), or -1
    std::string where;               // "file:line" of its Shape directive
    bool quadric() const { return kind == Sphere || kind == Disk || kind == Cylinder; }
    bool has_alpha() const { return alpha_tex >= 0 || alpha < 1; }
    size_t primitive_count() const
    {
        return kind == Triangles ? indices.size() / 3 : kind == Bilinear ? indices.size() / 4 : 1;
    }
};

// pbrt-v4's object instancing: the shapes of an ObjectBegin block (Shape::object), placed in the world by
// each ObjectInstance of its name with the transform world_from_object (the CTM at the ObjectInstance; the
// shapes keep the CTM they had inside the block, so a point of a shape goes to the world by the instance's
// transform times its own, as pbrt-v4 composes them).
struct ObjectDef {
    std::string name, where;  // where: its ObjectBegin
};
struct Instance {
    int object = -1;  // Scene::objects index
    Mat4 world_from_object, object_from_world;
    std::string where;  // its ObjectInstance
};

struct Camera {
    Mat4 world_from_camera;  // pbrt camera space: +z forward, +y up
    double fov = 90;         // degrees, along the shorter image axis (pbrt)
    double lens_radius = 0, focal_distance = 1e6;
    int medium = -1;         // the medium the camera is in (Scene::media index; pbrt-v4's outside medium at Camera)
};

struct Scene {
    Camera camera;
    int width = 256, height = 256;      // the film's full resolution
    // The part of the film rendered, as pbrt-v4's film reads it (film_window()): "cropwindow" (fractions of
    // the film, x0 x1 y0 y1) wins over "pixelbounds" (pixels x0 x1 y0 y1); the image is that part.
    bool has_crop = false, has_pixel_bounds = false;
    float crop[4] = {0, 1, 0, 1};
    int pixel_bounds[4] = {0, 0, 0, 0};
    double max_component = HUGE_VAL;    // Film "maxcomponentvalue": each sample scaled so that the largest of its
                                        // CIE XYZ components (the cie1931 sensor's values) is at most this
    std::string film_filename;
    double shutter_open = 0, shutter_close = 1;  // the Camera's; pbrt-v4's exposure time is their difference
    double film_scale = 1;              // pbrt-v4's imaging ratio: exposure time * iso / 100
    PixelFilter pixel_filter;           // a pbrt-v4 file's (gaussian without a PixelFilter line); else the unit box
    std::string film_sensor = "cie1931";  // the only sensor modelled (pbrt-v4's default: CIE XYZ)
    double white_balance = 0;           // Film "whitebalance": the temperature (K) adapted to D65; 0 none
    std::string media_where;              // file:line of the first MakeNamedMedium, if any
    std::vector<Medium> media;            // the homogeneous ones (grid media are refused under "volpath")
    std::string sampler;        // the scene's Sampler directive (udm1's renderers use their own samplers)
    std::string sampler_where;  // its file:line ("" without one)
    int pixel_samples = 16;     // its "pixelsamples" (pbrt-v4's default 16)
    std::string integrator = "volpath";  // pbrt-v4's default (without media the same image as "path")
    int max_depth = 5;
    // pbrt-v4's integrators without light sampling (simplepath "samplelights" false, randomwalk) find
    // lights only where paths hit them: point, spot and distant lights are left out of the scene. Without
    // BSDF sampling ("samplebsdf" false, randomwalk) they sample directions uniformly, which finds no
    // specular lobe: udm1-pt refuses materials that have one (pt/material.h).
    bool light_sampling = true, bsdf_sampling = true;
    std::string integrator_where;  // the Integrator's file:line ("" without one)
    std::vector<Material> materials;
    std::vector<Texture> textures;  // referenced from material parameters "texture NAME" by name
    std::vector<AreaLight> lights;
    std::vector<LightSource> light_sources;
    std::vector<Shape> shapes;           // the world's and, with Shape::object set, the objects' (instanced only)
    std::vector<ObjectDef> objects;
    std::vector<Instance> instances;
    std::string source;  // file name, or "built-in NAME"
    std::string search_dir;  // pbrt-v4's folder for relative file names: the main scene file's ("" for the cwd)
    // What a geometry-only load left out, one "file:line: what" per kind of directive or parameter.
    std::vector<std::string> ignored;
    // What the renderers substitute or ignore because it does not change the image (an Integrator that
    // converges to the same image, an Accelerator), one "file:line: what" each, for the user to read.
    std::vector<std::string> notes;

    size_t triangle_count() const;  // in the world (an instanced shape's once per instance)
    // Axis-aligned bounds of everything in the world (for ray offsets and default cameras).
    void bounds(Vec3 *lo, Vec3 *hi) const;
    // The pixels rendered of a width x height film, as pbrt-v4 computes them from cropwindow (ceil of the
    // resolution times each fraction, in float) or pixelbounds (clipped to the film): window = x0, y0, x1, y1.
    // Throws SceneError if the window is empty.
    void film_window(int width, int height, int window[4]) const;
    // A 64-bit FNV-1a digest of what a render sees: geometry, materials, lights, camera, film size. Two scenes with
    // the same digest render the same image (cached references are keyed by it).
    uint64_t digest() const;
};

// A sphere of radius r (> 0) about the origin of object space, placed by world_from_object: false if that
// transform is not affine and invertible. Transforms within 1e-9 of a similarity make a world sphere.
bool make_sphere(const Mat4 &world_from_object, double r, Shape *s);
// Sphere s at a world point p on it: the point in object space, and the unit outward normal in world
// space (the object-space normal by the inverse transpose; before any flip for orientation).
Vec3 sphere_object_point(const Shape &s, Vec3 p);
Vec3 sphere_normal(const Shape &s, Vec3 p);
// The world-space bounds of sphere s.
void sphere_bounds(const Shape &s, Vec3 *lo, Vec3 *hi);
// A disk or cylinder (s->kind set, its parameters in object space) placed by world_from_object: false if
// that transform is not affine and invertible.
bool make_quadric(const Mat4 &world_from_object, Shape *s);
// The world-space bounds of any shape (a quadric: its object-space box's image).
void shape_bounds(const Shape &s, Vec3 *lo, Vec3 *hi);

// The unit geometric normal of triangle `prim` of a triangle shape, oriented as pbrt-v4 orients it:
// cross(p0 - p2, p1 - p2), towards the shading normals if the mesh has them, else flipped by
// ReverseOrientation (and by a transform that swaps handedness, folded into reverse_orientation).
Vec3 triangle_normal(const Shape &s, unsigned prim);

// Raster (px, py) in [0, width) x [0, height), y down, to a world-space ray (pbrt's perspective camera).
void camera_ray(const Scene &s, double px, double py, Vec3 *origin, Vec3 *dir);

// The same rays with the per-image work done once (camera_ray per sample recomputes it).
class CameraRays {
public:
    explicit CameraRays(const Scene &s);
    void ray(double px, double py, Vec3 *origin, Vec3 *dir) const;
    // pbrt's thin lens: (lu, lv) in [0, 1)^2 picks the point on the lens (concentric disk mapping);
    // the same as ray() when the camera's lens radius is 0
    void ray(double px, double py, double lu, double lv, Vec3 *origin, Vec3 *dir) const;
    bool has_lens() const { return lens_radius_ > 0; }
    // Without a lens, ray(px, py) in closed form: the origin, and the direction normalize(a + px b + py c)
    // (equal to ray()'s within rounding; for loops over many rays).
    void pinhole(Vec3 *origin, Vec3 *a, Vec3 *b, Vec3 *c) const;

private:
    Mat4 world_from_camera_;
    Vec3 origin_;
    double w_, h_, sx0_, sx_span_, sy1_, sy_span_, tan_half_fov_, lens_radius_, focal_distance_;
};

// What a renderer needs of a scene. Everything: the supported subset exactly, anything else is an
// error. Geometry (ambient occlusion): shapes, transforms, camera and film size; appearance
// (materials, textures, media, lights' emission, film and camera extras) is read for syntax and
// left out, and each kind left out is listed in Scene::ignored.
enum class Need { Everything, Geometry };

// pbrt-v4's rule for a file name in a scene (ResolveFilename): an absolute name as it is; a relative one in
// search_dir (the main scene file's folder, for names in included files too) if it exists there, else as
// given (relative to the working directory).
std::string resolve_path(const std::string &search_dir, const std::string &name);

// Load a scene by file name: .pbrt or .pbrt.gz (pbrt-v4 subset), .ply, .ply.gz or .obj (a mesh with a default camera and a
// grey diffuse material), or "builtin:NAME". Throws SceneError naming the file (and line).
Scene load_scene(const std::string &path, Need need = Need::Everything);

}  // namespace udm1scene
