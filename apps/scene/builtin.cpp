// builtin.cpp - the scenes built in code (see builtin.h).
#include "builtin.h"

#include "mesh_io.h"

#include <algorithm>

namespace udm1scene {

namespace {

int add_material(Scene &s, const std::string &type, Vec3 reflectance)
{
    Material m;
    m.type = type;
    Param p;
    p.type = "rgb";
    p.name = "reflectance";
    p.numbers = {reflectance.x, reflectance.y, reflectance.z};
    p.where = s.source;
    m.params.params.push_back(p);
    m.params.where = s.source;
    s.materials.push_back(m);
    return (int)s.materials.size() - 1;
}

// A quad p0 p1 p2 p3 as triangles (0 1 2) (2 3 0), like the Cornell box file.
void quad(Scene &s, int material, Vec3 a, Vec3 b, Vec3 c, Vec3 d, int light = -1)
{
    Shape sh;
    sh.where = s.source;
    for (Vec3 p : {a, b, c, d}) sh.P.insert(sh.P.end(), {(float)p.x, (float)p.y, (float)p.z});
    sh.indices = {0, 1, 2, 2, 3, 0};
    sh.material = material;
    sh.light = light;
    s.shapes.push_back(sh);
}

// The Cornell box blocks: 5 faces of 4 vertices each, indices (3 2 0)(2 1 0) per face.
void block(Scene &s, int material, const double (*P)[3])
{
    Shape sh;
    sh.where = s.source;
    for (int i = 0; i < 20; ++i) sh.P.insert(sh.P.end(), {(float)P[i][0], (float)P[i][1], (float)P[i][2]});
    for (uint32_t f = 0; f < 5; ++f)
        sh.indices.insert(sh.indices.end(), {4 * f + 3, 4 * f + 2, 4 * f, 4 * f + 2, 4 * f + 1, 4 * f});
    sh.material = material;
    s.shapes.push_back(sh);
}

void look(Scene &s, Vec3 eye, Vec3 at, Vec3 up, double fov)
{
    bool ok;
    Mat4 cfw = Mat4::look_at(eye, at, up, &ok);
    cfw.inverse(&s.camera.world_from_camera);
    s.camera.fov = fov;
}

Scene cornell()
{
    Scene s;
    s.source = "builtin:cornell";
    s.width = s.height = 1080;
    look(s, Vec3(278, 273, -800), Vec3(278, 273, 0), Vec3(0, 1, 0), 37.5);
    int grey = add_material(s, "diffuse", Vec3(0.73, 0.73, 0.73));
    int red = add_material(s, "diffuse", Vec3(0.65, 0.05, 0.05));
    int green = add_material(s, "diffuse", Vec3(0.12, 0.45, 0.15));
    AreaLight light;
    light.L = Vec3(1, 1, 1);
    light.scale = 20;
    light.where = s.source;
    s.lights.push_back(light);
    quad(s, grey, Vec3(343.0, 548.7, 227.0), Vec3(343.0, 548.7, 332.0), Vec3(213.0, 548.7, 332.0),
         Vec3(213.0, 548.7, 227.0), 0);
    quad(s, red, Vec3(552.8, 0.0, 0.0), Vec3(549.6, 0.0, 559.2), Vec3(556.0, 548.8, 559.2), Vec3(556.0, 548.8, 0.0));
    quad(s, green, Vec3(0.0, 0.0, 559.2), Vec3(0.0, 0.0, 0.0), Vec3(0.0, 548.8, 0.0), Vec3(0.0, 548.8, 559.2));
    quad(s, grey, Vec3(552.8, 0.0, 0.0), Vec3(0.0, 0.0, 0.0), Vec3(0.0, 0.0, 559.2), Vec3(549.6, 0.0, 559.2));
    quad(s, grey, Vec3(556.0, 548.8, 0.0), Vec3(556.0, 548.8, 559.2), Vec3(0.0, 548.8, 559.2), Vec3(0.0, 548.8, 0.0));
    quad(s, grey, Vec3(549.6, 0.0, 559.2), Vec3(0.0, 0.0, 559.2), Vec3(0.0, 548.8, 559.2), Vec3(556.0, 548.8, 559.2));
    static const double small[20][3] = {
        {130.0, 165.0, 65.0}, {82.0, 165.0, 225.0},  {240.0, 165.0, 272.0}, {290.0, 165.0, 114.0},
        {290.0, 0.0, 114.0},  {290.0, 165.0, 114.0}, {240.0, 165.0, 272.0}, {240.0, 0.0, 272.0},
        {130.0, 0.0, 65.0},   {130.0, 165.0, 65.0},  {290.0, 165.0, 114.0}, {290.0, 0.0, 114.0},
        {82.0, 0.0, 225.0},   {82.0, 165.0, 225.0},  {130.0, 165.0, 65.0},  {130.0, 0.0, 65.0},
        {240.0, 0.0, 272.0},  {240.0, 165.0, 272.0}, {82.0, 165.0, 225.0},  {82.0, 0.0, 225.0}};
    static const double tall[20][3] = {
        {423.0, 330.0, 247.0}, {265.0, 330.0, 296.0}, {314.0, 330.0, 456.0}, {472.0, 330.0, 406.0},
        {423.0, 0.0, 247.0},   {423.0, 330.0, 247.0}, {472.0, 330.0, 406.0}, {472.0, 0.0, 406.0},
        {472.0, 0.0, 406.0},   {472.0, 330.0, 406.0}, {314.0, 330.0, 456.0}, {314.0, 0.0, 456.0},
        {314.0, 0.0, 456.0},   {314.0, 330.0, 456.0}, {265.0, 330.0, 296.0}, {265.0, 0.0, 296.0},
        {265.0, 0.0, 296.0},   {265.0, 330.0, 296.0}, {423.0, 330.0, 247.0}, {423.0, 0.0, 247.0}};
    block(s, grey, small);
    block(s, grey, tall);
    return s;
}

Scene plane()
{
    Scene s;
    s.source = "builtin:plane";
    look(s, Vec3(0, 10, 0), Vec3(0, 0, 0), Vec3(0, 0, 1), 60);
    int grey = add_material(s, "diffuse", Vec3(0.5, 0.5, 0.5));
    double L = 1e4;
    quad(s, grey, Vec3(-L, 0, -L), Vec3(L, 0, -L), Vec3(L, 0, L), Vec3(-L, 0, L));
    return s;
}

Scene box(bool emitting)
{
    Scene s;
    s.source = emitting ? "builtin:furnace-box" : "builtin:box";
    look(s, Vec3(0, 0, -0.5), Vec3(0, 0, 1), Vec3(0, 1, 0), 90);
    int grey = add_material(s, "diffuse", Vec3(0.5, 0.5, 0.5));
    Vec3 c[8];
    for (int i = 0; i < 8; ++i) c[i] = Vec3(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1);
    const int faces[6][4] = {{0, 1, 3, 2}, {4, 6, 7, 5}, {0, 4, 5, 1}, {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 5, 7, 3}};
    for (const auto &f : faces) {
        int light = -1;
        if (emitting) { /* every face emits L = 1 on both sides */
            AreaLight l;
            l.twosided = true;
            l.where = s.source;
            s.lights.push_back(l);
            light = (int)s.lights.size() - 1;
        }
        quad(s, grey, c[f[0]], c[f[1]], c[f[2]], c[f[3]], light);
    }
    return s;
}

Scene furnace_sphere()
{
    Scene s;
    s.source = "builtin:furnace";
    look(s, Vec3(0, 0, 0), Vec3(0, 0, 1), Vec3(0, 1, 0), 90);
    int grey = add_material(s, "diffuse", Vec3(0.5, 0.5, 0.5));
    AreaLight l;
    l.twosided = true;
    l.where = s.source;
    s.lights.push_back(l);
    Shape sh;
    sh.where = s.source;
    make_sphere(Mat4(), 1, &sh);
    sh.material = grey;
    sh.light = 0;
    s.shapes.push_back(sh);
    return s;
}

Scene wall()
{
    Scene s;
    s.source = "builtin:wall";
    look(s, Vec3(0, 3, -6), Vec3(0, 0, 0), Vec3(0, 1, 0), 60);
    int grey = add_material(s, "diffuse", Vec3(0.5, 0.5, 0.5));
    double L = 1e5;
    quad(s, grey, Vec3(-L, 0, -L), Vec3(L, 0, -L), Vec3(L, 0, 0), Vec3(-L, 0, 0));  // floor, z < 0
    quad(s, grey, Vec3(-L, 0, 0), Vec3(L, 0, 0), Vec3(L, L, 0), Vec3(-L, L, 0));    // wall, z = 0
    return s;
}

}  // namespace

std::vector<std::string> builtin_names() { return {"cornell", "plane", "box", "wall", "furnace", "furnace-box"}; }

Scene builtin_scene(const std::string &name)
{
    if (name == "cornell") return cornell();
    if (name == "plane") return plane();
    if (name == "box") return box(false);
    if (name == "furnace") return furnace_sphere();
    if (name == "furnace-box") return box(true);
    if (name == "wall") return wall();
    throw SceneError("builtin:" + name + ": no such built-in scene (cornell, plane, box, wall, furnace, furnace-box)");
}

Scene mesh_scene(const std::string &path)
{
    Scene s;
    s.source = path;
    Shape sh;
    sh.where = path;
    std::string lower = path;
    std::transform(lower.begin(), lower.end(), lower.begin(), ::tolower);
    if (lower.size() >= 4 && lower.compare(lower.size() - 4, 4, ".obj") == 0) read_obj(path, Mat4(), &sh);
    else read_ply(path, Mat4(), &sh);
    if (sh.indices.empty()) throw SceneError(path + ": the mesh has no faces");
    sh.material = add_material(s, "diffuse", Vec3(0.5, 0.5, 0.5));
    s.shapes.push_back(sh);
    Vec3 lo, hi;
    s.bounds(&lo, &hi);
    Vec3 c = (lo + hi) * 0.5;
    double r = std::max(1e-9, length(hi - lo) * 0.5);
    look(s, c + Vec3(0.6 * r, 0.8 * r, -2.2 * r), c, Vec3(0, 1, 0), 45);
    return s;
}

}  // namespace udm1scene
