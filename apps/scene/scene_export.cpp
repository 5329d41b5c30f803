// scene_export.cpp - see scene_export.h.
#include "scene_export.h"

#include "udm1app/cli.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace udm1pt {

using udm1app::Error;
using udm1scene::Vec3;

namespace {

std::string num(double v)
{
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    return buf;
}

std::string vec(Vec3 v) { return "[" + num(v.x) + ", " + num(v.y) + ", " + num(v.z) + "]"; }

std::string quoted(const std::string &s)
{
    std::string out = "\"";
    for (char c : s) {
        if (c == '"' || c == '\\') out += '\\';
        out += c;
    }
    return out + "\"";
}

void write_ply(const std::string &path, const udm1scene::Shape &s)
{
    std::ofstream f(path, std::ios::binary);
    if (!f) throw Error("cannot write '" + path + "'", 1);
    size_t nv = s.P.size() / 3, nt = s.indices.size() / 3;
    f << "ply\nformat binary_little_endian 1.0\nelement vertex " << nv
      << "\nproperty float x\nproperty float y\nproperty float z\n";
    if (!s.N.empty()) f << "property float nx\nproperty float ny\nproperty float nz\n";
    f << "element face " << nt << "\nproperty list uchar int vertex_indices\nend_header\n";
    for (size_t i = 0; i < nv; ++i) {
        f.write((const char *)&s.P[3 * i], 12);
        if (!s.N.empty()) f.write((const char *)&s.N[3 * i], 12);
    }
    for (size_t t = 0; t < nt; ++t) {
        unsigned char three = 3;
        f.write((const char *)&three, 1);
        int32_t idx[3] = {(int32_t)s.indices[3 * t], (int32_t)s.indices[3 * t + 1], (int32_t)s.indices[3 * t + 2]};
        if (s.reverse_orientation && s.N.empty()) std::swap(idx[1], idx[2]);  // the emitting side, as pbrt sees it
        f.write((const char *)idx, 12);
    }
    if (!f) throw Error("cannot write '" + path + "'", 1);
}

}  // namespace

void export_scene(const udm1scene::Scene &scene, int width, int height, int max_depth, const std::string &dir)
{
    if (!scene.light_sources.empty())  // scene.json describes shapes and their emission only
        throw Error(scene.light_sources[0].where + ": export writes area lights only, not a LightSource", 1);
    for (const udm1scene::Shape &s : scene.shapes)  // (scene.json has world shapes only)
        if (s.object >= 0) throw Error(s.where + ": export writes no ObjectBegin objects and instances", 1);
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec || !std::filesystem::is_directory(dir)) throw Error("cannot create the folder '" + dir + "'", 1);
    std::ostringstream js;
    const udm1scene::Mat4 &m = scene.camera.world_from_camera;
    Vec3 eye = m.point(Vec3(0, 0, 0)), target = m.point(Vec3(0, 0, 1)), up = m.vector(Vec3(0, 1, 0));
    // pbrt's camera space is left-handed (x right); the handedness of world_from_camera tells
    // whether the image is mirrored relative to a right-handed camera with the same eye, target, up
    double det = m.m[0][0] * (m.m[1][1] * m.m[2][2] - m.m[1][2] * m.m[2][1]) -
                 m.m[0][1] * (m.m[1][0] * m.m[2][2] - m.m[1][2] * m.m[2][0]) +
                 m.m[0][2] * (m.m[1][0] * m.m[2][1] - m.m[1][1] * m.m[2][0]);
    js << "{\n  \"source\": " << quoted(scene.source) << ",\n  \"width\": " << width << ", \"height\": " << height
       << ",\n  \"maxdepth\": " << max_depth << ",\n  \"camera\": {\"eye\": " << vec(eye) << ", \"target\": " << vec(target)
       << ", \"up\": " << vec(up) << ", \"fov\": " << num(scene.camera.fov) << ", \"fov_axis\": \"smaller\", "
       << "\"world_from_camera_determinant\": " << num(det) << "},\n  \"shapes\": [\n";
    for (size_t k = 0; k < scene.shapes.size(); ++k) {
        const udm1scene::Shape &s = scene.shapes[k];
        js << "    {";
        if (s.kind == udm1scene::Shape::Disk || s.kind == udm1scene::Shape::Cylinder || s.kind == udm1scene::Shape::Bilinear)
            throw Error(s.where + ": export writes triangle meshes and spheres, not a disk, cylinder or bilinear patch", 1);
        if (s.has_alpha()) throw Error(s.where + ": export does not write alpha cut-outs", 1);
        if (s.kind == udm1scene::Shape::Sphere && s.ellipsoid)  // scene.json has spheres by centre and radius
            throw Error(s.where + ": export writes spheres by centre and radius: this one, under a transform that is "
                                  "not a rotation and a uniform scale, is an ellipsoid",
                        1);
        if (s.kind == udm1scene::Shape::Sphere) {
            js << "\"sphere\": {\"center\": " << vec(s.center) << ", \"radius\": " << num(s.radius)
               << ", \"flip_normals\": " << (s.reverse_orientation ? "true" : "false") << "}";
        } else {
            std::string file = "shape_" + std::to_string(k) + ".ply";
            write_ply(dir + "/" + file, s);
            js << "\"ply\": " << quoted(file) << ", \"normals\": " << (s.N.empty() ? "false" : "true");
        }
        if (s.material >= 0) {
            const udm1scene::Material &mat = scene.materials[s.material];
            js << ", \"material\": {\"type\": " << quoted(mat.type);
            for (const udm1scene::Param &p : mat.params.params) {
                if (p.name == "type") continue;
                js << ", " << quoted(p.name) << ": ";
                if (p.type == "texture" && !p.strings.empty()) {  // a texture by name: {"texture": name}
                    js << "{\"texture\": " << quoted(p.strings[0]) << "}";
                } else if ((p.type == "spectrum" || p.type == "blackbody") && !p.numbers.empty()) {
                    js << "{\"" << p.type << "\": [";  // sampled or blackbody spectra as written
                    for (size_t i = 0; i < p.numbers.size(); ++i) js << (i ? ", " : "") << num(p.numbers[i]);
                    js << "]}";
                } else if (!p.numbers.empty()) {
                    if (p.numbers.size() == 1) js << num(p.numbers[0]);
                    else js << vec(Vec3(p.numbers[0], p.numbers[1], p.numbers.size() > 2 ? p.numbers[2] : 0));
                } else if (!p.strings.empty()) {
                    js << (p.type == "bool" ? p.strings[0] : quoted(p.strings[0]));
                } else {
                    js << "null";
                }
            }
            js << "}";
        } else {  // pbrt-v4's default material (default_material())
            js << ", \"material\": {\"type\": \"diffuse\", \"reflectance\": [0.5, 0.5, 0.5]}";
        }
        if (s.light >= 0) {
            const udm1scene::AreaLight &l = scene.lights[s.light];
            js << ", \"emission\": {\"L\": " << vec(l.L * l.scale) << ", \"twosided\": " << (l.twosided ? "true" : "false")
               << "}";
        }
        js << "}" << (k + 1 < scene.shapes.size() ? "," : "") << "\n";
    }
    js << "  ]\n}\n";
    std::ofstream f(dir + "/scene.json");
    f << js.str();
    if (!f) throw Error("cannot write '" + dir + "/scene.json'", 1);
}

}  // namespace udm1pt
