// pbrt_parser.cpp - the subset of the pbrt-v4 scene format that udm1's target
// scenes use (../shared/scenes: cornell-box, veach-mis; the Crown adds more).
// Anything else is refused with "file:line: ..." naming the directive or
// parameter: model only what a scene needs.
#include "pbrt_parser.h"

#include "file_read.h"

#include "mesh_io.h"
#include "spectrum.h"
#include "udm1app/one_line.h"

#include <algorithm>
#include <cmath>
#include <cctype>
#include <cerrno>
#include <cstdlib>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

namespace udm1scene {

namespace {

// Refused wherever it would matter: pbrt-v4 applies a matrix's projective part to points but not to
// directions and normals.
const char *const PROJECTIVE = "a projective transform (its bottom row is not 0 0 0 1) is not modelled";

// Raw scene text as an error message quotes it: one line, control characters escaped, cut when long.
std::string quote(const std::string &raw) { return udm1app::quote_raw(raw); }

struct Token {
    enum Kind { Word, String, Number, Open, Close, End } kind = End;
    std::string text;
    double number = 0;
    int line = 0;
};

class Lexer {
public:
    Lexer(std::string text, std::string file) : s_(std::move(text)), file_(std::move(file)) {}
    const std::string &file() const { return file_; }
    std::string where(int line) const { return file_ + ":" + std::to_string(line); }

    Token peek()
    {
        if (!has_peek_) {
            peek_ = next_token();
            has_peek_ = true;
        }
        return peek_;
    }
    Token next()
    {
        Token t = peek();
        has_peek_ = false;
        return t;
    }

private:
    Token next_token()
    {
        for (;;) {
            while (i_ < s_.size() && std::isspace((unsigned char)s_[i_])) {
                if (s_[i_] == '\n') ++line_;
                ++i_;
            }
            if (i_ < s_.size() && s_[i_] == '#') {
                while (i_ < s_.size() && s_[i_] != '\n') ++i_;
                continue;
            }
            break;
        }
        Token t;
        t.line = line_;
        if (i_ >= s_.size()) return t;
        char c = s_[i_];
        if (c == '[' || c == ']') {
            t.kind = c == '[' ? Token::Open : Token::Close;
            ++i_;
            return t;
        }
        if (c == '"') {
            size_t j = i_ + 1;
            while (j < s_.size() && s_[j] != '"' && s_[j] != '\n') ++j;
            if (j >= s_.size() || s_[j] != '"') throw SceneError(where(line_) + ": unterminated string");
            t.kind = Token::String;
            t.text = s_.substr(i_ + 1, j - i_ - 1);
            i_ = j + 1;
            return t;
        }
        size_t j = i_;
        while (j < s_.size() && !std::isspace((unsigned char)s_[j]) && s_[j] != '[' && s_[j] != ']' && s_[j] != '"' &&
               s_[j] != '#')
            ++j;
        t.text = s_.substr(i_, j - i_);
        i_ = j;
        if (std::isdigit((unsigned char)c) || c == '-' || c == '+' || c == '.') {
            char *end = nullptr;
            errno = 0;
            t.number = std::strtod(t.text.c_str(), &end);
            if (*end != '\0' || errno == ERANGE || !std::isfinite(t.number))
                throw SceneError(where(line_) + ": malformed number '" + quote(t.text) + "'");
            t.kind = Token::Number;
        } else {
            t.kind = Token::Word;
        }
        return t;
    }

    std::string s_, file_;
    size_t i_ = 0;
    int line_ = 1;
    Token peek_;
    bool has_peek_ = false;
};

struct State {
    Mat4 ctm;
    int material = -1;
    int light_template = -1;  // an AreaLightSource of this block (copied per shape)
    bool reverse = false;
};

class Parser {
public:
    Parser(Scene &scene, Need need) : scene_(scene), geometry_only_(need == Need::Geometry) {}

    void parse_file(const std::string &path, int depth)
    {
        if (depth > 8) throw SceneError(path + ": Include nested too deeply");
        Lexer lex(read_regular_file(path, "scene file"), path);
        std::string dir = path.find('/') == std::string::npos ? "" : path.substr(0, path.find_last_of('/') + 1);
        std::string outer_dir = dir_;
        dir_ = dir;
        for (;;) {
            Token t = lex.next();
            if (t.kind == Token::End) break;
            if (t.kind != Token::Word)
                throw SceneError(lex.where(t.line) + ": expected a directive, found '" + quote(t.text) + "'");
            directive(lex, t, dir, depth);
        }
        dir_ = outer_dir;
    }

    void finish()
    {
        if (!camera_set_) { /* pbrt's default camera: at the origin looking down +z */
            scene_.camera.world_from_camera = Mat4();
        }
        if (!scene_.light_sampling) {  // lights that only light sampling finds
            std::vector<LightSource> &ls = scene_.light_sources;
            size_t before = ls.size();
            ls.erase(std::remove_if(ls.begin(), ls.end(), [](const LightSource &l) { return l.kind != LightSource::Infinite; }),
                     ls.end());
            if (ls.size() != before)
                scene_.notes.push_back(scene_.integrator_where + ": point, spot and distant lights are left out: without "
                                                                 "light sampling pbrt-v4 never finds them");
        }
    }

private:
    static int line(const Token &t) { return t.line; }

    double number(Lexer &lex)
    {
        Token t = lex.next();
        if (t.kind != Token::Number) throw SceneError(lex.where(t.line) + ": expected a number, found '" + quote(t.text) + "'");
        return t.number;
    }

    std::string string_arg(Lexer &lex, const std::string &what)
    {
        Token t = lex.next();
        if (t.kind != Token::String)
            throw SceneError(lex.where(t.line) + ": " + what + " needs a quoted name, found '" + quote(t.text) + "'");
        return t.text;
    }

    std::vector<double> numbers_in_brackets_or_n(Lexer &lex, size_t n, const std::string &what)
    {
        std::vector<double> v;
        Token t = lex.peek();
        if (t.kind == Token::Open) {
            lex.next();
            while (lex.peek().kind == Token::Number) v.push_back(lex.next().number);
            Token c = lex.next();
            if (c.kind != Token::Close) throw SceneError(lex.where(c.line) + ": " + what + ": expected ']'");
        } else {
            for (size_t k = 0; k < n; ++k) v.push_back(number(lex));
        }
        if (v.size() != n)
            throw SceneError(lex.where(t.line) + ": " + what + " needs " + std::to_string(n) + " numbers, got " +
                             std::to_string(v.size()));
        return v;
    }

    ParamSet params(Lexer &lex, int directive_line)
    {
        ParamSet ps;
        ps.where = lex.where(directive_line);
        while (lex.peek().kind == Token::String) {
            Token decl = lex.next();
            std::istringstream in(decl.text);
            Param p;
            in >> p.type >> p.name;
            std::string extra;
            if (p.type.empty() || p.name.empty() || (in >> extra))
                throw SceneError(lex.where(decl.line) + ": parameter \"" + quote(decl.text) + "\" is not \"type name\"");
            static const char *types[] = {"integer", "float",  "point2", "vector2", "point3", "vector3", "normal",
                                          "normal3", "point",  "vector", "rgb",     "string", "bool",    "texture",
                                          "spectrum", "blackbody"};
            bool known = false;
            for (const char *k : types) known |= p.type == k;
            if (!known) throw SceneError(lex.where(decl.line) + ": unknown parameter type '" + quote(p.type) + "'");
            p.where = lex.where(decl.line);
            bool textual = p.type == "string" || p.type == "bool" || p.type == "texture";
            auto take = [&](const Token &v) {
                if (v.kind == Token::Number) {
                    if (textual) throw SceneError(lex.where(v.line) + ": '" + quote(p.name) + "' needs quoted values");
                    p.numbers.push_back(v.number);
                } else if (v.kind == Token::String) {
                    if (!textual && p.type != "spectrum")
                        throw SceneError(lex.where(v.line) + ": '" + quote(p.name) + "' needs numbers, found \"" + quote(v.text) + "\"");
                    p.strings.push_back(v.text);
                } else if (v.kind == Token::Word && p.type == "bool" && (v.text == "true" || v.text == "false")) {
                    p.strings.push_back(v.text);
                } else {
                    throw SceneError(lex.where(v.line) + ": bad value '" + quote(v.text) + "' for '" + quote(p.name) + "'");
                }
            };
            Token v = lex.next();
            if (v.kind == Token::Open) {
                while (lex.peek().kind != Token::Close) {
                    Token e = lex.next();
                    if (e.kind == Token::End) throw SceneError(lex.where(e.line) + ": '" + quote(p.name) + "': missing ']'");
                    take(e);
                }
                lex.next();
            } else {
                take(v);
            }
            if (p.type == "spectrum" && !geometry_only_) resolve_spectrum(p);
            ps.params.push_back(std::move(p));
        }
        return ps;
    }

    // A "spectrum" parameter names a spectrum udm1 knows, or a file of (wavelength, value) pairs relative
    // to the scene file's folder (pbrt-v4 tries the two in that order): the file's pairs replace its name.
    // Pairs are checked (an even count, increasing wavelengths).
    void resolve_spectrum(Param &p)
    {
        if (p.strings.size() > 1 || (p.strings.size() == 1 && !p.numbers.empty()))
            throw SceneError(p.where + ": '" + p.name + "' needs one spectrum: a name or (wavelength, value) pairs");
        if (p.strings.size() == 1 && !named_spectrum(p.strings[0])) {
            const std::string &file = p.strings[0];
            std::string full = file.size() && file[0] == '/' ? file : dir_ + file;
            Spectrum s;
            try {
                s = read_spectrum_file(full);
            } catch (const SceneError &e) {
                throw SceneError(p.where + ": '" + p.name + "': \"" + file + "\" is not a named spectrum that udm1 knows (" +
                                 known_spectra() + ") nor a spectrum file (" + e.what() + ")");
            }
            p.strings.clear();
            for (size_t i = 0; i < s.nm.size(); ++i) p.numbers.push_back(s.nm[i]), p.numbers.push_back(s.value[i]);
        }
        if (p.strings.empty()) spectrum_from_pairs(p.numbers, p.where + ": '" + p.name + "'");
    }

    void only(const ParamSet &ps, std::initializer_list<const char *> allowed, const std::string &what,
              bool appearance = false)
    {
        for (const Param &p : ps.params) {
            bool ok = false;
            for (const char *a : allowed) ok |= p.name == a;
            if (ok) continue;
            if (appearance && geometry_only_) ignore(p.where, what + " '" + p.name + "'");
            else throw SceneError(p.where + ": " + what + ": unsupported parameter '" + p.name + "'");
        }
    }

    // A geometry-only load leaves this out: note the first place of each kind.
    void ignore(const std::string &where, const std::string &what)
    {
        if (ignored_kinds_.insert(what).second) scene_.ignored.push_back(where + ": " + what);
    }

    // Appearance directives a geometry-only load skips: quoted arguments, then parameters.
    void skip(Lexer &lex, const Token &t)
    {
        while (lex.peek().kind == Token::String && lex.peek().text.find(' ') == std::string::npos) lex.next();
        params(lex, t.line);
        ignore(lex.where(t.line), t.text);
    }

    void transform(const Mat4 &t) { st_.ctm = st_.ctm * t; }

    // A light's emission parameter as linear sRGB: an rgb triple as it is, a blackbody or any other
    // spectrum (pairs, a named spectrum or a file) at luminance 1, as pbrt-v4 normalizes a light's
    // spectrum before its scale (spectrum.h).
    Vec3 emission(const ParamSet &ps, const std::string &name, const std::string &what)
    {
        const Param *p = ps.find(name);
        Vec3 rgb;
        if (p->type == "rgb") {
            if (!ps.get_rgb(name, &rgb)) throw SceneError(p->where + ": " + what + ": \"rgb " + name + "\" needs 3 numbers");
            if (rgb.x < 0 || rgb.y < 0 || rgb.z < 0) throw SceneError(p->where + ": " + what + ": negative emission");
            return rgb;
        }
        if (p->type == "blackbody") {
            if (p->numbers.size() != 1 || !(p->numbers[0] >= 1000 && p->numbers[0] <= 40000))
                throw SceneError(p->where + ": " + what + ": \"blackbody " + name + "\" needs one temperature in 1000..40000 K");
            return illuminant_rgb(Spectrum::blackbody(p->numbers[0]), p->where);
        }
        if (p->type == "spectrum") {
            const Spectrum *named = p->strings.size() == 1 ? named_spectrum(p->strings[0]) : nullptr;
            return illuminant_rgb(named ? *named : spectrum_from_pairs(p->numbers, p->where), p->where);
        }
        throw SceneError(p->where + ": " + what + ": '" + name + "' must be rgb, blackbody or spectrum");
    }

    // The directives, one handler each. A handler reads its arguments from c.lex; c.here is the
    // directive's "file:line", c.dir the scene file's folder, c.depth the Include depth.
    struct Call {
        Lexer &lex;
        const Token &t;
        const std::string &here, &dir;
        int depth;
    };
    using Handler = void (Parser::*)(const Call &);

    void directive(Lexer &lex, const Token &t, const std::string &dir, int depth)
    {
        static const std::map<std::string, Handler> HANDLERS = {
            {"LookAt", &Parser::on_LookAt},
            {"Translate", &Parser::on_Translate},
            {"Scale", &Parser::on_Scale},
            {"Rotate", &Parser::on_Rotate},
            {"Transform", &Parser::on_Transform},
            {"ConcatTransform", &Parser::on_Transform},
            {"Identity", &Parser::on_Identity},
            {"Camera", &Parser::on_Camera},
            {"Film", &Parser::on_Film},
            {"Sampler", &Parser::on_Sampler},
            {"Accelerator", &Parser::on_Accelerator},
            {"Integrator", &Parser::on_Integrator},
            {"PixelFilter", &Parser::on_PixelFilter},
            {"WorldBegin", &Parser::on_WorldBegin},
            {"AttributeBegin", &Parser::on_AttributeBegin},
            {"TransformBegin", &Parser::on_AttributeBegin},  // (pbrt-v4 reads TransformBegin/End as AttributeBegin/End)
            {"AttributeEnd", &Parser::on_AttributeEnd},
            {"TransformEnd", &Parser::on_AttributeEnd},
            {"ReverseOrientation", &Parser::on_ReverseOrientation},
            {"Material", &Parser::on_Material},
            {"MakeNamedMaterial", &Parser::on_MakeNamedMaterial},
            {"NamedMaterial", &Parser::on_NamedMaterial},
            {"AreaLightSource", &Parser::on_AreaLightSource},
            {"LightSource", &Parser::on_LightSource},
            {"Shape", &Parser::on_Shape},
            {"Include", &Parser::on_Include},
            {"Import", &Parser::on_Include},
            {"Texture", &Parser::on_Texture},
            {"MakeNamedMedium", &Parser::on_MakeNamedMedium},
            {"MediumInterface", &Parser::on_MediumInterface}};
        // what a geometry-only load (udm1-ao) skips: appearance, lights, media
        static const std::set<std::string> APPEARANCE = {"AreaLightSource", "LightSource", "Texture",   "MakeNamedMedium",
                                                         "MediumInterface", "ColorSpace",  "Option", "Attribute"};
        // pbrt-v4's blocks: options before WorldBegin, the scene's description after it
        static const std::set<std::string> OPTIONS = {"Camera",      "Sampler",    "Film",      "PixelFilter",
                                                      "Accelerator", "Integrator", "WorldBegin"};
        static const std::set<std::string> WORLD = {"ReverseOrientation", "AttributeBegin",    "AttributeEnd",
                                                    "TransformBegin",     "TransformEnd",      "LightSource",
                                                    "Shape",              "Texture",           "Material",
                                                    "MakeNamedMaterial",  "NamedMaterial",     "AreaLightSource"};
        const std::string here = lex.where(t.line);
        if (in_world_ && OPTIONS.count(t.text))
            throw SceneError(here + ": " + t.text + " after WorldBegin: pbrt-v4 takes it only before");
        if (!in_world_ && WORLD.count(t.text))
            throw SceneError(here + ": " + t.text + " before WorldBegin: pbrt-v4 takes it only after");
        if (geometry_only_ && APPEARANCE.count(t.text)) return skip(lex, t);  // the emitters' shapes stay geometry
        auto it = HANDLERS.find(t.text);
        if (it == HANDLERS.end()) throw SceneError(here + ": unsupported directive '" + quote(t.text) + "'");
        (this->*it->second)(Call{lex, t, here, dir, depth});
    }

    void on_LookAt(const Call &c)
    {
        Lexer &lex = c.lex;
        const std::string &here = c.here;
        std::vector<double> v;
        for (int k = 0; k < 9; ++k) v.push_back(number(lex));
        bool ok;
        Mat4 m = Mat4::look_at(Vec3(v[0], v[1], v[2]), Vec3(v[3], v[4], v[5]), Vec3(v[6], v[7], v[8]), &ok);
        if (!ok) throw SceneError(here + ": LookAt: degenerate eye, target and up");
        transform(m);
    }

    void on_Translate(const Call &c)
    {
        Lexer &lex = c.lex;
        std::vector<double> v = numbers_in_brackets_or_n(lex, 3, "Translate");
        transform(Mat4::translate(Vec3(v[0], v[1], v[2])));
    }

    void on_Scale(const Call &c)
    {
        Lexer &lex = c.lex;
        std::vector<double> v = numbers_in_brackets_or_n(lex, 3, "Scale");
        transform(Mat4::scale(Vec3(v[0], v[1], v[2])));
    }

    void on_Rotate(const Call &c)
    {
        Lexer &lex = c.lex;
        const std::string &here = c.here;
        std::vector<double> v = numbers_in_brackets_or_n(lex, 4, "Rotate");
        if (v[1] == 0 && v[2] == 0 && v[3] == 0) throw SceneError(here + ": Rotate: zero axis");
        transform(Mat4::rotate(v[0], Vec3(v[1], v[2], v[3])));
    }

    void on_Transform(const Call &c)
    {
        Lexer &lex = c.lex;
        const std::string &d = c.t.text;
        std::vector<double> v = numbers_in_brackets_or_n(lex, 16, d);
        Mat4 m;  // pbrt lists the matrix column by column
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 4; ++j) m.m[i][j] = v[j * 4 + i];
        if (d == "Transform") st_.ctm = m;
        else transform(m);
    }

    void on_Identity(const Call &)
    {
        st_.ctm = Mat4();
    }

    void on_Camera(const Call &c)
    {
        Lexer &lex = c.lex;
        const Token &t = c.t;
        const std::string &here = c.here;
        std::string type = string_arg(lex, "Camera");
        ParamSet ps = params(lex, t.line);
        if (type != "perspective") throw SceneError(here + ": Camera \"" + type + "\" is not supported (perspective only)");
        only(ps, {"fov", "lensradius", "focaldistance"}, "Camera", true);
        scene_.camera.fov = ps.get_float("fov", 90);
        scene_.camera.lens_radius = ps.get_float("lensradius", 0);
        scene_.camera.focal_distance = ps.get_float("focaldistance", 1e6);
        if (!(scene_.camera.fov > 0 && scene_.camera.fov < 180)) throw SceneError(here + ": Camera fov outside (0, 180)");
        if (!geometry_only_) {  // (a geometry-only load renders through a pinhole)
            const Param *lr = ps.find("lensradius"), *fd = ps.find("focaldistance");
            if (scene_.camera.lens_radius < 0)
                throw SceneError(lr->where + ": Camera: lensradius " + number_text(scene_.camera.lens_radius) +
                                 " is negative (0 is a pinhole)");
            if (scene_.camera.lens_radius > 0 && !(scene_.camera.focal_distance > 0))
                throw SceneError(fd->where + ": Camera: focaldistance " + number_text(scene_.camera.focal_distance) +
                                 " with a lens is not modelled: pbrt-v4 focuses a lens on the plane at that distance, "
                                 "which at 0 is the lens itself (rays along the lens plane) and below 0 behind it");
        }
        // (a transform that is not rigid maps the rays as pbrt-v4 maps them, which warns that it may be wrong)
        if (!st_.ctm.affine()) throw SceneError(here + ": Camera: " + PROJECTIVE);
        if (!st_.ctm.inverse(&scene_.camera.world_from_camera)) throw SceneError(here + ": Camera: singular transform");
        camera_set_ = true;
    }

    void on_Film(const Call &c)
    {
        Lexer &lex = c.lex;
        const Token &t = c.t;
        const std::string &here = c.here;
        std::string type = string_arg(lex, "Film");
        ParamSet ps = params(lex, t.line);
        if (type != "rgb") throw SceneError(here + ": Film \"" + type + "\" is not supported (rgb only)");
        only(ps, {"xresolution", "yresolution", "filename", "iso", "exposuretime", "sensor", "whitebalance"}, "Film",
             true);
        // pbrt-v4's imaging ratio (exposure time x ISO / 100) scales the image; the sensor's spectral
        // response and white balance have no RGB counterpart: the film is a plain RGB sensor
        scene_.film_scale = ps.get_float("exposuretime", 1.0) * ps.get_float("iso", 100.0) / 100;
        scene_.film_sensor = ps.get_string("sensor", "cie1931");
        if (!(scene_.film_scale > 0 && scene_.film_scale < 1e6))
            throw SceneError(here + ": Film: exposuretime x iso / 100 must be positive");
        scene_.width = ps.get_int("xresolution", 1280);
        scene_.height = ps.get_int("yresolution", 720);
        scene_.film_filename = ps.get_string("filename", "");
        if (scene_.width < 1 || scene_.height < 1 || scene_.width > 65536 || scene_.height > 65536)
            throw SceneError(here + ": Film resolution outside 1..65536");
    }

    void on_Sampler(const Call &c)
    {
        Lexer &lex = c.lex;
        const Token &t = c.t;
        const std::string &here = c.here;
        scene_.sampler = string_arg(lex, "Sampler");
        ParamSet ps = params(lex, t.line);
        scene_.sampler_where = here;
        scene_.pixel_samples = ps.get_int("pixelsamples", 16);
        if (scene_.pixel_samples < 1 || scene_.pixel_samples > (1 << 24))
            throw SceneError(here + ": Sampler: pixelsamples " + std::to_string(scene_.pixel_samples) + " outside 1..2^24");
    }

    void on_Accelerator(const Call &c)
    {
        Lexer &lex = c.lex;
        const Token &t = c.t;
        const std::string &here = c.here;
        std::string type = string_arg(lex, "Accelerator");
        params(lex, t.line);
        scene_.notes.push_back(here + ": Accelerator \"" + type + "\" ignored: rays are traced by Embree (the image does not depend on it)");
    }

    void on_Integrator(const Call &c)
    {
        Lexer &lex = c.lex;
        const Token &t = c.t;
        const std::string &here = c.here;
        scene_.integrator = string_arg(lex, "Integrator");
        ParamSet ps = params(lex, t.line);
        if (geometry_only_) {
            ignore(here, "Integrator");
        } else {  // udm1-pt is a unidirectional path tracer; volpath without media is the same
            const std::string &in = scene_.integrator;
            if (in != "path" && in != "volpath" && in != "simplepath" && in != "randomwalk")
                throw SceneError(here + ": Integrator \"" + in + "\" is not supported (path, volpath without media; "
                                        "simplepath and randomwalk render as path)");
            // each integrator's own parameters (pbrt-v4 refuses the others as unused)
            if (in == "path" || in == "volpath") only(ps, {"maxdepth", "lightsampler", "regularize"}, "Integrator \"" + in + "\"");
            else if (in == "simplepath") only(ps, {"maxdepth", "samplelights", "samplebsdf"}, "Integrator \"simplepath\"");
            else only(ps, {"maxdepth"}, "Integrator \"randomwalk\"");
            if (ps.get_bool("regularize", false))
                throw SceneError(ps.find("regularize")->where + ": Integrator: regularize (a biased image) is not supported");
            std::string sampler = ps.get_string("lightsampler", "bvh");
            if (sampler != "bvh" && sampler != "power" && sampler != "uniform" && sampler != "exhaustive")
                throw SceneError(ps.find("lightsampler")->where + ": Integrator: lightsampler \"" + sampler +
                                 "\" is not one of pbrt-v4's (bvh, power, uniform, exhaustive)");
            // without light sampling (simplepath's samplelights false, randomwalk) pbrt-v4 finds lights only
            // where paths hit them; without BSDF sampling (samplebsdf false, randomwalk) it samples directions
            // uniformly, which never finds a specular lobe: the renderer models both (Scene)
            scene_.light_sampling = in == "randomwalk" ? false : ps.get_bool("samplelights", true);
            scene_.bsdf_sampling = in == "randomwalk" ? false : ps.get_bool("samplebsdf", true);
            scene_.integrator_where = here;
            if (in == "simplepath" || in == "randomwalk") {  // the same image in the limit, found another way
                scene_.notes.push_back(here + ": Integrator \"" + in + "\" renders as \"path\" (the same image it "
                                              "converges to; noise differs)");
                scene_.integrator = "path";
            }
            if (ps.find("lightsampler"))
                scene_.notes.push_back(here + ": Integrator: lightsampler ignored (it changes the noise, not the image; "
                                              "udm1-pt chooses lights by their importance, with MIS)");
        }
        scene_.max_depth = ps.get_int("maxdepth", 5);
        if (scene_.max_depth < 0 || scene_.max_depth > 1000)
            throw SceneError(here + ": Integrator: maxdepth " + std::to_string(scene_.max_depth) + " outside 0..1000");
    }

    void on_PixelFilter(const Call &c)
    {
        Lexer &lex = c.lex;
        const Token &t = c.t;
        string_arg(lex, "PixelFilter");
        params(lex, t.line);  // the renderers use their own box filter
    }

    void on_WorldBegin(const Call &)
    {
        st_ = State();
        in_world_ = true;
    }

    void on_AttributeBegin(const Call &)
    {
        stack_.push_back(st_);
    }

    void on_AttributeEnd(const Call &c)
    {
        const std::string &d = c.t.text;
        const std::string &here = c.here;
        if (stack_.empty()) throw SceneError(here + ": " + d + " without a matching begin");
        State s = stack_.back();
        stack_.pop_back();
        st_ = s;
    }

    void on_ReverseOrientation(const Call &)
    {
        st_.reverse = !st_.reverse;
    }

    void on_Material(const Call &c)
    {
        Lexer &lex = c.lex;
        const Token &t = c.t;
        Material m;
        m.type = string_arg(lex, "Material");
        m.params = params(lex, t.line);
        scene_.materials.push_back(m);
        st_.material = (int)scene_.materials.size() - 1;
    }

    void on_MakeNamedMaterial(const Call &c)
    {
        Lexer &lex = c.lex;
        const Token &t = c.t;
        const std::string &here = c.here;
        std::string name = string_arg(lex, "MakeNamedMaterial");
        Material m;
        m.params = params(lex, t.line);
        m.name = name;
        m.type = m.params.get_string("type", "");
        if (m.type.empty()) throw SceneError(here + ": MakeNamedMaterial \"" + name + "\" has no \"string type\"");
        scene_.materials.push_back(m);
        named_[name] = (int)scene_.materials.size() - 1;
    }

    void on_NamedMaterial(const Call &c)
    {
        Lexer &lex = c.lex;
        const std::string &here = c.here;
        std::string name = string_arg(lex, "NamedMaterial");
        auto it = named_.find(name);
        if (it == named_.end()) throw SceneError(here + ": NamedMaterial \"" + name + "\" was not made");
        st_.material = it->second;
    }

    void on_AreaLightSource(const Call &c)
    {
        Lexer &lex = c.lex;
        const Token &t = c.t;
        const std::string &here = c.here;
        std::string type = string_arg(lex, "AreaLightSource");
        ParamSet ps = params(lex, t.line);
        if (type != "diffuse") throw SceneError(here + ": AreaLightSource \"" + type + "\" is not supported (diffuse only)");
        only(ps, {"L", "scale", "twosided"}, "AreaLightSource");
        AreaLight l;
        if (ps.find("L")) l.L = emission(ps, "L", "AreaLightSource");
        l.scale = ps.get_float("scale", 1.0);
        l.twosided = ps.get_bool("twosided", false);
        l.where = here;
        if (!(l.scale >= 0) || l.L.x < 0 || l.L.y < 0 || l.L.z < 0)
            throw SceneError(here + ": AreaLightSource: negative emission");
        templates_.push_back(l);
        st_.light_template = (int)templates_.size() - 1;
    }

    void on_LightSource(const Call &c)
    {
        Lexer &lex = c.lex;
        const Token &t = c.t;
        const std::string &dir = c.dir;
        light_source(lex, t, dir);
    }

    void on_Shape(const Call &c)
    {
        Lexer &lex = c.lex;
        const Token &t = c.t;
        const std::string &dir = c.dir;
        shape(lex, t, dir);
    }

    void on_Include(const Call &c)
    {
        Lexer &lex = c.lex;
        const std::string &d = c.t.text;
        const std::string &here = c.here;
        const std::string &dir = c.dir;
        int depth = c.depth;
        std::string file = string_arg(lex, d);
        std::string full = file.size() && file[0] == '/' ? file : dir + file;
        if (!std::ifstream(full, std::ios::binary)) throw SceneError(here + ": " + d + ": " + full + ": cannot open the scene file");
        parse_file(full, depth + 1);
    }

    void on_Texture(const Call &c)
    {
        Lexer &lex = c.lex;
        const Token &t = c.t;
        const std::string &d = c.t.text;
        const std::string &here = c.here;
        const std::string &dir = c.dir;
        Texture tx;
        tx.name = string_arg(lex, d), tx.kind = string_arg(lex, d), tx.type = string_arg(lex, d);
        ParamSet ps = params(lex, t.line);
        tx.where = here;
        if (tx.kind != "float" && tx.kind != "spectrum")
            throw SceneError(here + ": Texture \"" + tx.name + "\": kind \"" + tx.kind + "\" is not float or spectrum");
        if (tx.type == "imagemap") {
            only(ps, {"filename", "encoding", "invert", "scale", "wrap", "filter"}, "Texture imagemap");
            std::string file = ps.get_string("filename", "");
            if (file.empty()) throw SceneError(here + ": Texture imagemap needs \"string filename\"");
            tx.filename = file[0] == '/' ? file : dir + file;
            std::string enc = ps.get_string("encoding", "sRGB");
            if (enc != "sRGB" && enc != "linear")
                throw SceneError(here + ": Texture imagemap: encoding \"" + enc + "\" is not supported (sRGB, linear)");
            tx.srgb = enc == "sRGB";
            tx.invert = ps.get_bool("invert", false);
            tx.scale = ps.get_float("scale", 1.0);
            if (ps.get_string("wrap", "repeat") != "repeat")
                throw SceneError(here + ": Texture imagemap: only \"repeat\" wrapping is supported");
            std::string filter = ps.get_string("filter", "bilinear");
            if (filter != "bilinear" && filter != "point")
                throw SceneError(here + ": Texture imagemap: filter \"" + filter + "\" is not supported (bilinear, point)");
            tx.point = filter == "point";
        } else if (tx.type == "scale") {
            only(ps, {"tex", "scale"}, "Texture scale");
            const Param *p = ps.find("tex");
            if (!p || p->type != "texture" || p->strings.size() != 1)
                throw SceneError(here + ": Texture scale needs \"texture tex\"");
            auto it = textures_.find(p->strings[0]);
            if (it == textures_.end()) throw SceneError(p->where + ": texture \"" + p->strings[0] + "\" was not made");
            tx.tex = it->second;
            tx.scale = ps.get_float("scale", 1.0);
        } else {
            throw SceneError(here + ": Texture \"" + tx.type + "\" is not supported (imagemap, scale)");
        }
        scene_.textures.push_back(tx);
        textures_[tx.name] = (int)scene_.textures.size() - 1;
    }

    void on_MakeNamedMedium(const Call &c)
    {
        Lexer &lex = c.lex;
        const Token &t = c.t;
        const std::string &d = c.t.text;
        const std::string &here = c.here;
        std::string name = string_arg(lex, d);
        ParamSet ps = params(lex, t.line);
        std::string type = ps.get_string("type", "");
        if (type != "homogeneous")
            throw SceneError(here + ": MakeNamedMedium \"" + name + "\": type \"" + type + "\" is not supported (homogeneous)");
        only(ps, {"type", "sigma_a", "sigma_s", "scale", "g", "Le", "Lescale", "preset"}, "MakeNamedMedium");
        media_.insert(name);
        if (scene_.media_where.empty()) scene_.media_where = here;
    }

    void on_MediumInterface(const Call &c)
    {
        Lexer &lex = c.lex;
        const std::string &d = c.t.text;
        const std::string &here = c.here;
        std::string inside = string_arg(lex, d), outside = inside;
        if (lex.peek().kind == Token::String) outside = string_arg(lex, d);
        for (const std::string &m : {inside, outside})
            if (!m.empty() && !media_.count(m)) throw SceneError(here + ": MediumInterface: medium \"" + m + "\" was not made");
    }

    // An emitting sphere under transform m: refused where pbrt-v4's image of it is not consistent. pbrt-v4
    // intersects a sphere in object space (any affine transform) but samples a sphere light as the sphere
    // of its object-space radius about its world centre, with normals flipped by ReverseOrientation
    // only: under a transform that scales or shears it, or (one-sided) swaps handedness, light sampling
    // and the rays that hit the light see different lights.
    void sphere_light_transform(const std::string &here, const Mat4 &m, bool twosided)
    {
        double scale;
        if (!m.similarity(1e-9, &scale) || std::fabs(scale - 1) > 1e-9)
            throw SceneError(here + ": an emitting sphere under a transform that scales or shears it is not modelled: "
                                    "pbrt-v4 samples a sphere light as the sphere of its \"float radius\" about its "
                                    "centre, not as the shape it intersects, so its image is not consistent (give the "
                                    "size by the radius)");
        if (m.determinant3() < 0 && !twosided)
            throw SceneError(here + ": a one-sided emitting sphere under a transform that swaps handedness is not "
                                    "modelled: pbrt-v4 flips the normals where rays hit it but not where it samples "
                                    "it, so its image is not consistent (use ReverseOrientation, or \"bool twosided\" "
                                    "true)");
    }

    // LightSource "point" | "spot" | "distant" | "infinite", placed by the current transform, with pbrt-v4's
    // parameters, defaults and normalization: the emission spectrum at 1 nit (or as rgb), times "scale";
    // "power" (point, spot) or "illuminance" (distant, infinite) in its place where given.
    void light_source(Lexer &lex, const Token &t, const std::string &dir)
    {
        const std::string here = lex.where(t.line);
        std::string type = string_arg(lex, "LightSource");
        ParamSet ps = params(lex, t.line);
        const double PI = 3.14159265358979323846;
        LightSource l;
        l.where = here;
        const Mat4 &m = st_.ctm;
        if (!m.affine()) throw SceneError(here + ": LightSource \"" + type + "\": " + PROJECTIVE);
        double similar_scale;
        const bool similar = m.similarity(1e-9, &similar_scale);
        auto emitted = [&](const char *name) { return ps.find(name) ? emission(ps, name, "LightSource") : Vec3(1, 1, 1); };
        double scale = ps.get_float("scale", 1.0), power = ps.get_float("power", -1), lux = ps.get_float("illuminance", -1);
        if (!(scale >= 0) || !std::isfinite(scale)) throw SceneError(here + ": LightSource: scale must not be negative");
        if (type == "point" || type == "spot") {
            only(ps, {"I", "scale", "power", "from", "to", "coneangle", "conedeltaangle"}, "LightSource \"" + type + "\"");
            if (type == "point" && (ps.find("to") || ps.find("coneangle") || ps.find("conedeltaangle")))
                throw SceneError(here + ": LightSource \"point\": unsupported parameter (to, coneangle, conedeltaangle are a spot's)");
            Vec3 from = ps.get_point("from", Vec3()), I = emitted("I");
            l.position = m.point(from);
            double solid_angle = 4 * PI;  // of the emission at full intensity, for "power"
            if (type == "spot") {
                if (!similar)
                    throw SceneError(here + ": LightSource \"spot\" under a transform that is not a rotation and a "
                                            "uniform scale is not modelled: pbrt-v4 shapes its cone by the transform "
                                            "but bounds it unshaped when it chooses lights, so its image is not "
                                            "consistent");
                l.kind = LightSource::Spot;
                Vec3 axis = m.vector(ps.get_point("to", Vec3(0, 0, 1)) - from);
                if (!(length(axis) > 0)) throw SceneError(here + ": LightSource \"spot\": from and to coincide");
                l.direction = normalize(axis);
                double cone = ps.get_float("coneangle", 30), delta = ps.get_float("conedeltaangle", 5);
                if (!(cone > 0 && cone <= 180 && delta >= 0 && delta <= cone))
                    throw SceneError(here + ": LightSource \"spot\": coneangle must be in (0, 180] and conedeltaangle in [0, coneangle]");
                l.cos_end = std::cos(cone * PI / 180), l.cos_start = std::cos((cone - delta) * PI / 180);
                solid_angle = 2 * PI * ((1 - l.cos_start) + (l.cos_start - l.cos_end) / 2);
            }
            if (power > 0) scale *= power / solid_angle;  // (an rgb I keeps its own magnitude, as in pbrt-v4)
            l.L = I * scale;
        } else if (type == "distant") {
            only(ps, {"L", "scale", "from", "to", "illuminance"}, "LightSource \"distant\"");
            l.kind = LightSource::Distant;
            Vec3 w = m.vector(ps.get_point("from", Vec3()) - ps.get_point("to", Vec3(0, 0, 1)));
            if (!(length(w) > 0)) throw SceneError(here + ": LightSource \"distant\": from and to coincide");
            l.direction = normalize(w);
            Vec3 L = emitted("L");
            if (lux > 0) scale *= lux;
            l.L = L * scale;
        } else if (type == "infinite") {
            only(ps, {"L", "scale", "filename", "illuminance", "portal"}, "LightSource \"infinite\"");
            if (const Param *p = ps.find("portal")) throw SceneError(p->where + ": LightSource \"infinite\": portals are not supported");
            l.kind = LightSource::Infinite;
            l.world_from_light = m;
            Mat4 inv;
            if (!m.inverse(&inv)) throw SceneError(here + ": LightSource \"infinite\": singular transform");
            std::string file = ps.get_string("filename", "");
            if (!file.empty()) {
                if (ps.find("L")) throw SceneError(here + ": LightSource \"infinite\": both \"L\" and \"filename\" given");
                if (!similar)
                    throw SceneError(here + ": LightSource \"infinite\" with an image under a transform that is not a "
                                            "rotation and a uniform scale is not modelled: pbrt-v4 samples it by the "
                                            "untransformed image's density, so its image is not consistent");
                l.filename = file[0] == '/' ? file : dir + file;
                l.illuminance = lux;  // needs the image: the renderer applies it
                l.L = Vec3(scale, scale, scale);
            } else {
                Vec3 L = emitted("L");
                if (lux > 0) scale *= lux / PI;  // a uniform sky's illuminance is pi L
                l.L = L * scale;
            }
        } else {
            throw SceneError(here + ": LightSource \"" + type + "\" is not supported (point, spot, distant, infinite)");
        }
        scene_.light_sources.push_back(l);
    }

    void shape(Lexer &lex, const Token &t, const std::string &dir)
    {
        const std::string here = lex.where(t.line);
        std::string type = string_arg(lex, "Shape");
        ParamSet ps = params(lex, t.line);
        Shape s;
        s.where = here;
        s.material = st_.material;
        s.reverse_orientation = st_.reverse;
        if (st_.light_template >= 0) { /* every shape of the block gets its own emitter */
            scene_.lights.push_back(templates_[st_.light_template]);
            s.light = (int)scene_.lights.size() - 1;
        }
        // a transform that swaps handedness flips the geometric normal too (pbrt)
        const Mat4 &m = st_.ctm;
        if (m.determinant3() < 0) s.reverse_orientation = !s.reverse_orientation;
        if (type == "trianglemesh") {
            only(ps, {"indices", "P", "N", "uv"}, "trianglemesh");  // ("st": pbrt-v4 reads it only when upgrading a file)
            const Param *P = ps.find("P", "point3"), *I = ps.find("indices", "integer");
            if (!P || P->numbers.size() % 3 || P->numbers.empty())
                throw SceneError(here + ": trianglemesh needs \"point3 P\" with 3 numbers per vertex");
            size_t nv = P->numbers.size() / 3;
            std::vector<double> idx;
            if (I) idx = I->numbers;
            else if (nv == 3) idx = {0, 1, 2};
            else throw SceneError(here + ": trianglemesh needs \"integer indices\"");
            if (idx.size() % 3) throw SceneError(I->where + ": trianglemesh: the indices are not a multiple of 3");
            for (double v : idx)
                if (!(v >= 0 && v < (double)nv) || v != std::floor(v))  // NaN too; no cast before the range check
                    throw SceneError((I ? I->where : here) + ": trianglemesh: index " + number_text(v) +
                                     " out of range (" + std::to_string(nv) + " vertices)");
            for (size_t k = 0; k < nv; ++k) {
                Vec3 p = m.point(Vec3(P->numbers[3 * k], P->numbers[3 * k + 1], P->numbers[3 * k + 2]));
                s.P.insert(s.P.end(), {(float)p.x, (float)p.y, (float)p.z});
            }
            for (double v : idx) s.indices.push_back((uint32_t)v);
            if (const Param *N = ps.find("N", "normal")) {
                if (N->numbers.size() != 3 * nv) throw SceneError(N->where + ": trianglemesh: N needs one normal per vertex");
                for (size_t k = 0; k < nv; ++k) {
                    Vec3 n = normalize(m.normal(Vec3(N->numbers[3 * k], N->numbers[3 * k + 1], N->numbers[3 * k + 2])));
                    s.N.insert(s.N.end(), {(float)n.x, (float)n.y, (float)n.z});
                }
            }
            const Param *uv = ps.find("uv", "point2");
            if (uv) {
                if (uv->numbers.size() != 2 * nv) throw SceneError(uv->where + ": trianglemesh: uv needs 2 numbers per vertex");
                for (double v : uv->numbers) s.UV.push_back((float)v);
            }
        } else if (type == "plymesh") {
            only(ps, {"filename", "displacement", "edgelength"}, "plymesh");
            if (const Param *disp = ps.find("displacement")) {
                if (!geometry_only_) throw SceneError(disp->where + ": plymesh displacement is not supported");
                ignore(disp->where, "plymesh displacement (the mesh is used undisplaced)");
            }
            std::string file = ps.get_string("filename", "");
            if (file.empty()) throw SceneError(here + ": plymesh needs \"string filename\"");
            try {  // the PLY's own complaint, and where the scene asked for it
                read_ply(file[0] == '/' ? file : dir + file, m, &s);
            } catch (const SceneError &e) {
                throw SceneError(here + ": plymesh: " + e.what());
            }
        } else if (type == "sphere") {
            only(ps, {"radius"}, "sphere");
            double r = ps.get_float("radius", 1.0);
            if (!(r > 0)) throw SceneError(here + ": sphere radius must be positive");
            if (!m.affine()) throw SceneError(here + ": sphere: " + PROJECTIVE);
            if (!make_sphere(m, r, &s)) throw SceneError(here + ": sphere: singular transform");
            if (s.light >= 0) sphere_light_transform(here, m, templates_[st_.light_template].twosided);
        } else {
            throw SceneError(here + ": Shape \"" + type + "\" is not supported (trianglemesh, plymesh, sphere)");
        }
        if (s.kind == Shape::Triangles && s.indices.empty()) throw SceneError(here + ": the shape has no triangles");
        if (!s.N.empty()) {  // vertex normals: pbrt-v4 transforms them by the inverse transpose (normal()) and
                             // ReverseOrientation flips them; the geometric normal then faces them
            if (!m.affine()) throw SceneError(here + ": " + type + " with normals: " + PROJECTIVE);
            if (st_.reverse)
                for (float &x : s.N) x = -x;
        }
        scene_.shapes.push_back(std::move(s));
    }

    Scene &scene_;
    State st_;
    std::vector<State> stack_;
    std::map<std::string, int> named_;
    std::vector<AreaLight> templates_;  // AreaLightSource of the blocks; each shape gets a copy
    bool camera_set_ = false, in_world_ = false;
    bool geometry_only_ = false;
    std::set<std::string> ignored_kinds_;
    std::set<std::string> media_;  // MakeNamedMedium names
    std::map<std::string, int> textures_;
    std::string dir_;  // the folder of the file being read (relative file names)
};

}  // namespace

Scene parse_pbrt(const std::string &path, Need need)
{
    Scene scene;
    scene.source = path;
    Parser p(scene, need);
    p.parse_file(path, 0);
    p.finish();
    if (scene.shapes.empty()) throw SceneError(path + ": the scene has no shapes");
    return scene;
}

}  // namespace udm1scene
