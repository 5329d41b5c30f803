// mesh_io.cpp - PLY and OBJ readers (see mesh_io.h).
#include "mesh_io.h"

#include "file_read.h"
#include "udm1app/one_line.h"

#include <cmath>
#include <cerrno>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>

namespace udm1scene {

namespace {

enum class Type { I8, U8, I16, U16, I32, U32, F32, F64, Bad };

Type type_of(const std::string &t)
{
    if (t == "char" || t == "int8") return Type::I8;
    if (t == "uchar" || t == "uint8") return Type::U8;
    if (t == "short" || t == "int16") return Type::I16;
    if (t == "ushort" || t == "uint16") return Type::U16;
    if (t == "int" || t == "int32") return Type::I32;
    if (t == "uint" || t == "uint32") return Type::U32;
    if (t == "float" || t == "float32") return Type::F32;
    if (t == "double" || t == "float64") return Type::F64;
    return Type::Bad;
}

size_t size_of(Type t)
{
    switch (t) {
    case Type::I8: case Type::U8: return 1;
    case Type::I16: case Type::U16: return 2;
    case Type::I32: case Type::U32: case Type::F32: return 4;
    default: return 8;
    }
}

struct Property {
    std::string name;
    Type type = Type::Bad;
    bool list = false;
    Type count_type = Type::Bad;
};

struct Element {
    std::string name;
    size_t count = 0;
    std::vector<Property> props;
};

// Reads values from the body: ASCII tokens or binary in either byte order.
class Reader {
public:
    Reader(const std::string &data, size_t pos, int format, std::string path)
        : d_(data), p_(pos), format_(format), path_(std::move(path)) {}

    double value(Type t, const char *what)
    {
        if (format_ == 0) return ascii(what);
        size_t n = size_of(t);
        if (p_ + n > d_.size()) throw SceneError(path_ + ": truncated: the file ends inside the " + udm1app::quote_raw(what));
        unsigned char b[8];
        std::memcpy(b, d_.data() + p_, n);
        p_ += n;
        if (format_ == 2)  // big endian
            for (size_t i = 0; i < n / 2; ++i) std::swap(b[i], b[n - 1 - i]);
        switch (t) {
        case Type::I8: return (double)(int8_t)b[0];
        case Type::U8: return (double)b[0];
        case Type::I16: { int16_t v; std::memcpy(&v, b, 2); return v; }
        case Type::U16: { uint16_t v; std::memcpy(&v, b, 2); return v; }
        case Type::I32: { int32_t v; std::memcpy(&v, b, 4); return v; }
        case Type::U32: { uint32_t v; std::memcpy(&v, b, 4); return v; }
        case Type::F32: { float v; std::memcpy(&v, b, 4); return v; }
        default: { double v; std::memcpy(&v, b, 8); return v; }
        }
    }

private:
    double ascii(const char *what)
    {
        while (p_ < d_.size() && std::isspace((unsigned char)d_[p_])) ++p_;
        if (p_ >= d_.size()) throw SceneError(path_ + ": truncated: the file ends inside the " + udm1app::quote_raw(what));
        const char *s = d_.c_str() + p_;
        char *end = nullptr;
        errno = 0;
        double v = std::strtod(s, &end);
        if (end == s || errno == ERANGE) throw SceneError(path_ + ": malformed number in the " + udm1app::quote_raw(what));
        p_ += (size_t)(end - s);
        return v;
    }

    const std::string &d_;
    size_t p_;
    int format_;  // 0 ascii, 1 little endian, 2 big endian
    std::string path_;
};

std::string read_all(const std::string &path)
{
    return read_regular_file(path, "mesh file");
}

// A list's length as read (any number type): a whole number below 2^31, else the file is refused (a huge
// or fractional value cast to size_t is undefined behaviour; found by fuzzing).
size_t list_count(double c, const std::string &path)
{
    if (!(c >= 0 && c < 2147483648.0) || c != (double)(size_t)c)
        throw SceneError(path + ": a list length of " + std::to_string(c) + " is not a whole number below 2^31");
    return (size_t)c;
}

void add_vertex(Shape *s, const Mat4 &xf, Vec3 p)
{
    Vec3 w = xf.point(p);
    s->P.insert(s->P.end(), {(float)w.x, (float)w.y, (float)w.z});
}

}  // namespace

void read_ply(const std::string &path, const Mat4 &xf, Shape *shape)
{
    std::string data = read_all(path);
    size_t end = data.find("end_header");
    if (data.compare(0, 3, "ply") != 0 || end == std::string::npos)
        throw SceneError(path + ": not a PLY file (no 'ply' ... 'end_header')");
    size_t body = data.find('\n', end);
    if (body == std::string::npos) throw SceneError(path + ": truncated after end_header");
    ++body;
    std::istringstream header(data.substr(0, end));
    std::string line;
    int format = -1;
    std::vector<Element> elements;
    int ln = 0;
    while (std::getline(header, line)) {
        ++ln;
        std::istringstream in(line);
        std::string word;
        in >> word;
        if (word == "format") {
            std::string f;
            in >> f;
            format = f == "ascii" ? 0 : f == "binary_little_endian" ? 1 : f == "binary_big_endian" ? 2 : -1;
            if (format < 0) throw SceneError(path + ":" + std::to_string(ln) + ": unknown PLY format '" + udm1app::quote_raw(f) + "'");
        } else if (word == "element") {
            Element e;
            long long count = -1;
            in >> e.name >> count;
            if (count < 0) throw SceneError(path + ":" + std::to_string(ln) + ": bad element count");
            e.count = (size_t)count;
            elements.push_back(e);
        } else if (word == "property") {
            if (elements.empty()) throw SceneError(path + ":" + std::to_string(ln) + ": property before any element");
            Property p;
            std::string t;
            in >> t;
            if (t == "list") {
                std::string ct, it;
                in >> ct >> it >> p.name;
                p.list = true;
                p.count_type = type_of(ct);
                p.type = type_of(it);
                if (p.count_type == Type::Bad || p.type == Type::Bad || p.count_type == Type::F32 ||
                    p.count_type == Type::F64)
                    throw SceneError(path + ":" + std::to_string(ln) + ": unsupported list types '" + udm1app::quote_raw(ct + " " + it) + "'");
            } else {
                p.type = type_of(t);
                in >> p.name;
                if (p.type == Type::Bad)
                    throw SceneError(path + ":" + std::to_string(ln) + ": unsupported property type '" + udm1app::quote_raw(t) + "'");
            }
            elements.back().props.push_back(p);
        }
    }
    if (format < 0) throw SceneError(path + ": no format line");
    Reader r(data, body, format, path);
    size_t base = shape->P.size() / 3, nverts = 0;
    bool has_normals = false, has_uv = false;
    for (const Element &e : elements) {
        if (e.name == "vertex") {
            nverts = e.count;
            int ix = -1, iy = -1, iz = -1, inx = -1, iny = -1, inz = -1, iu = -1, iv = -1;
            for (size_t k = 0; k < e.props.size(); ++k) {
                const std::string &n = e.props[k].name;
                if (n == "x") ix = (int)k;
                if (n == "y") iy = (int)k;
                if (n == "z") iz = (int)k;
                if (n == "nx") inx = (int)k;
                if (n == "ny") iny = (int)k;
                if (n == "nz") inz = (int)k;
                if (n == "u" || n == "s" || n == "texture_u" || n == "texture_s") iu = (int)k;
                if (n == "v" || n == "t" || n == "texture_v" || n == "texture_t") iv = (int)k;
            }
            if (ix < 0 || iy < 0 || iz < 0) throw SceneError(path + ": the vertices have no x, y, z");
            has_normals = inx >= 0 && iny >= 0 && inz >= 0;
            has_uv = iu >= 0 && iv >= 0;
            std::vector<double> v(e.props.size());
            for (size_t i = 0; i < e.count; ++i) {
                for (size_t k = 0; k < e.props.size(); ++k) {
                    const Property &p = e.props[k];
                    if (p.list) {
                        size_t c = list_count(r.value(p.count_type, "vertex list"), path);
                        for (size_t j = 0; j < c; ++j) r.value(p.type, "vertex list");
                        v[k] = 0;
                    } else {
                        v[k] = r.value(p.type, "vertices");
                    }
                }
                add_vertex(shape, xf, Vec3(v[ix], v[iy], v[iz]));
                if (has_normals) {
                    Vec3 n = normalize(xf.normal(Vec3(v[inx], v[iny], v[inz])));
                    shape->N.insert(shape->N.end(), {(float)n.x, (float)n.y, (float)n.z});
                }
                if (has_uv) shape->UV.insert(shape->UV.end(), {(float)v[iu], (float)v[iv]});
            }
        } else if (e.name == "face") {
            int il = -1;
            for (size_t k = 0; k < e.props.size(); ++k)
                if (e.props[k].list && (e.props[k].name == "vertex_indices" || e.props[k].name == "vertex_index"))
                    il = (int)k;
            if (il < 0) throw SceneError(path + ": the faces have no vertex_indices list");
            std::vector<uint32_t> poly;
            for (size_t i = 0; i < e.count; ++i) {
                for (size_t k = 0; k < e.props.size(); ++k) {
                    const Property &p = e.props[k];
                    if (!p.list) {
                        r.value(p.type, "faces");
                        continue;
                    }
                    double c = r.value(p.count_type, "faces");
                    if (!(c >= 0 && c <= 1e6) || c != std::floor(c))  // NaN too
                        throw SceneError(path + ": face " + std::to_string(i) + " has a bad vertex count (" + number_text(c) + ")");
                    poly.clear();
                    for (size_t j = 0; j < (size_t)c; ++j) {
                        double idx = r.value(p.type, "faces");
                        if ((int)k != il) continue;
                        if (!(idx >= 0 && idx < (double)nverts) || idx != std::floor(idx))  // NaN too
                            throw SceneError(path + ": face " + std::to_string(i) + ": vertex index " +
                                             number_text(idx) + " out of range (" +
                                             std::to_string(nverts) + " vertices)");
                        poly.push_back((uint32_t)(base + (size_t)idx));
                    }
                    if ((int)k == il && poly.size() >= 3)
                        for (size_t j = 1; j + 1 < poly.size(); ++j)
                            shape->indices.insert(shape->indices.end(), {poly[0], poly[j], poly[j + 1]});
                }
            }
        } else {  // skip other elements (one without properties holds no data, whatever its count)
            for (size_t i = 0; i < e.count && !e.props.empty(); ++i)
                for (const Property &p : e.props) {
                    if (!p.list) {
                        r.value(p.type, e.name.c_str());
                        continue;
                    }
                    size_t c = list_count(r.value(p.count_type, e.name.c_str()), path);
                    for (size_t j = 0; j < c; ++j) r.value(p.type, e.name.c_str());
                }
        }
    }
    if (nverts == 0) throw SceneError(path + ": no vertices");
    if (!has_normals) shape->N.clear();
    if (!has_uv) shape->UV.clear();
}

void read_obj(const std::string &path, const Mat4 &xf, Shape *shape)
{
    std::string data = read_all(path);
    std::istringstream in(data);
    std::string line;
    std::vector<Vec3> vs;
    int ln = 0;
    size_t base = shape->P.size() / 3;
    auto bad = [&](const std::string &msg) { return SceneError(path + ":" + std::to_string(ln) + ": " + msg); };
    auto num = [&](std::istringstream &s) {
        std::string t;
        if (!(s >> t)) throw bad("missing number");
        char *end = nullptr;
        errno = 0;
        double v = std::strtod(t.c_str(), &end);
        if (*end || errno == ERANGE || !std::isfinite(v)) throw bad("malformed number '" + udm1app::quote_raw(t) + "'");
        return v;
    };
    while (std::getline(in, line)) {
        ++ln;
        std::istringstream s(line);
        std::string w;
        if (!(s >> w) || w[0] == '#') continue;
        if (w == "v") {
            double x = num(s), y = num(s), z = num(s);
            vs.emplace_back(x, y, z);
            add_vertex(shape, xf, vs.back());
        } else if (w == "f") {
            std::vector<uint32_t> poly;
            std::string tok;
            while (s >> tok) {
                char *end = nullptr;
                long v = std::strtol(tok.c_str(), &end, 10);
                if (end == tok.c_str() || (*end && *end != '/')) throw bad("malformed face vertex '" + udm1app::quote_raw(tok) + "'");
                long idx = v > 0 ? v - 1 : (long)vs.size() + v;
                if (v == 0 || idx < 0 || idx >= (long)vs.size())
                    throw bad("vertex index " + std::to_string(v) + " out of range (" + std::to_string(vs.size()) +
                              " vertices so far)");
                poly.push_back((uint32_t)(base + (size_t)idx));
            }
            if (poly.size() < 3) throw bad("a face needs 3 vertices");
            for (size_t j = 1; j + 1 < poly.size(); ++j)
                shape->indices.insert(shape->indices.end(), {poly[0], poly[j], poly[j + 1]});
        }
        // vn, vt, g, o, s, usemtl, mtllib, l, p: not needed for geometry
    }
    if (vs.empty()) throw SceneError(path + ": no vertices");
}

}  // namespace udm1scene
