// pbrt_parser.cpp - the subset of the pbrt-v4 scene format that the scenes of the pbrt-v4 collection use,
// read as pbrt-v4's parser and scene builder read it: one token stream through Includes, file names from
// the main scene file's folder, gzip-compressed files, names (materials, textures, objects) resolved when the
// scene is complete. Anything else is refused with "file:line: ..." naming the directive or parameter: model
// only what a scene needs.
#include "pbrt_parser.h"

#include "displacement.h"
#include "file_read.h"

#include "loop_subdivision.h"
#include "medium_presets.h"
#include "mesh_io.h"
#include "spectrum.h"
#include "tabulated_bsdf.h"
#include "textures.h"
#include "white_balance.h"
#include "udm1app/one_line.h"

#include <sys/stat.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <map>
#include <memory>
#include <set>
#include <sstream>

namespace udm1scene {

namespace {

// Refused wherever it would matter: pbrt-v4 applies a matrix's projective part to points but not to
// directions and normals.
const char *const PROJECTIVE = "a projective transform (its bottom row is not 0 0 0 1) is not modelled";

// How far a light's transform may be from a rotation and a uniform scale (relative, in its Gram matrix) and
// still be taken as one: scene files write matrices with about six significant digits, which leaves a
// rotation's columns unit and orthogonal to about 1e-6; what pbrt-v4 renders inconsistently differs by far more.
const double RIGID_TOLERANCE = 1e-5;

// Raw scene text as an error message quotes it: one line, control characters escaped, cut when long.
std::string quote(const std::string &raw) { return udm1app::quote_raw(raw); }

struct Token {
    enum Kind { Word, String, Number, Open, Close, End } kind = End;
    std::string text;
    double number = 0;
    int line = 0;
    const std::string *file = nullptr;  // the file it is in (names kept by the parser)
};

std::string where(const Token &t) { return *t.file + ":" + std::to_string(t.line); }

std::string short_number(double v)  // (for notes: 0.8, not 0.80000000000000004)
{
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.6g", v);
    return buf;
}

// One file's text as tokens.
class FileLexer {
public:
    FileLexer(std::string text, const std::string *file) : s_(std::move(text)), file_(file) {}

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
        t.file = file_;
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
            if (j >= s_.size() || s_[j] != '"') throw SceneError(where(t) + ": unterminated string");
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
                throw SceneError(where(t) + ": malformed number '" + quote(t.text) + "'");
            t.kind = Token::Number;
        } else {
            t.kind = Token::Word;
        }
        return t;
    }

private:
    std::string s_;
    const std::string *file_;
    size_t i_ = 0;
    int line_ = 1;
};

// pbrt-v4's token stream: an Include pushes its file, whose tokens come next; at its end the including
// file's follow. A directive's parameters therefore go on past the end of an included file into the file
// that included it, as pbrt-v4 reads them.
class Lexer {
public:
    void push(std::string text, const std::string *file) { files_.push_back(std::make_unique<FileLexer>(std::move(text), file)); }
    size_t depth() const { return files_.size(); }

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
            Token t = files_.back()->next_token();
            if (t.kind != Token::End || files_.size() == 1) return t;
            files_.pop_back();  // an included file ends: the including one goes on
        }
    }

    std::vector<std::unique_ptr<FileLexer>> files_;
    Token peek_;
    bool has_peek_ = false;
};

// The targets of pbrt-v4's Attribute directive, whose parameters are defaults for the directives of that kind.
enum Target { SHAPE, LIGHT, MATERIAL, MEDIUM, TEXTURE, TARGETS };
const char *const TARGET_NAMES[TARGETS] = {"shape", "light", "material", "medium", "texture"};

struct State {
    Mat4 ctm[2];     // pbrt-v4's transforms at the start and the end time (ActiveTransform, TransformTimes)
    int active = 3;  // the transforms directives change: bit 0 the start one, bit 1 the end one
    int material = -1;           // the current Material (Scene::materials index), -1 the default
    std::string named_material;  // or the NamedMaterial's name, resolved after parsing as pbrt-v4 resolves it
    std::string named_where;     // (its file:line)
    int light_template = -1;  // an AreaLightSource of this block (copied per shape)
    bool reverse = false;
    std::string inside, outside;  // the current MediumInterface's media ("" none), and its file:line
    std::string media_where;
    std::vector<Param> attributes[TARGETS];  // Attribute defaults in force (in the order given)
};

class Parser {
public:
    Parser(Scene &scene, Need need) : scene_(scene), geometry_only_(need == Need::Geometry) {}

    // The main scene file: its folder is where pbrt-v4 looks for every relative file name (resolve_path).
    void parse_main(const std::string &path)
    {
        if (!geometry_only_) scene_.pixel_filter = PixelFilter::defaults("gaussian");  // pbrt-v4's default filter
        size_t slash = path.find_last_of('/');
        scene_.search_dir = slash == std::string::npos ? "" : path.substr(0, slash + 1);
        Lexer lex;
        lex.push(read_scene_file(path, "scene file"), name(path));
        run(lex);
    }

    void finish()
    {
        if (!stack_.empty())  // pbrt-v4: "Missing end to AttributeBegin"
            throw SceneError(blocks_.back().second + ": " + (blocks_.back().first == 'o' ? "ObjectBegin" : "AttributeBegin") +
                             " is never ended");
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
        // pbrt-v4's imaging ratio: the Camera's exposure time (shutterclose - shutteropen) times the Film's iso / 100
        scene_.film_scale = (scene_.shutter_close - scene_.shutter_open) * iso_ / 100;
        if (!(scene_.film_scale > 0 && scene_.film_scale < 1e6))
            throw SceneError((!film_where_.empty() ? film_where_ : !shutter_where_.empty() ? shutter_where_ : scene_.source) +
                             ": the exposure time (the Camera's shutterclose - shutteropen) times the Film's iso / 100 "
                             "must be in (0, 1e6)");
        if (!shutter_where_.empty() && !geometry_only_)
            scene_.notes.push_back(shutter_where_ + ": Camera shutteropen, shutterclose: nothing in the scene moves (no "
                                                    "motion blur); the exposure time " + short_number(scene_.shutter_close - scene_.shutter_open) +
                                   " scales the image, as pbrt-v4's imaging ratio");
        // what pbrt-v4 resolves when it creates the scene, after reading every file
        for (const PendingMaterial &pm : pending_materials_) {
            auto it = named_.find(pm.name);
            if (it == named_.end())
                throw SceneError(pm.where + ": NamedMaterial \"" + quote(pm.name) + "\" was not made (by a MakeNamedMaterial anywhere in the scene)");
            scene_.shapes[pm.shape].material = it->second.index;
        }
        resolve_textures();
        resolve_displacements();
        resolve_instances();
        // (after the named materials: a shape's NamedMaterial "interface" may be made after the shape)
        if (!geometry_only_) resolve_media(), interface_lights();
    }

private:

    double number(Lexer &lex)
    {
        Token t = lex.next();
        if (t.kind != Token::Number) throw SceneError(where(t) + ": expected a number, found '" + quote(t.text) + "'");
        return t.number;
    }

    std::string string_arg(Lexer &lex, const std::string &what)
    {
        Token t = lex.next();
        if (t.kind != Token::String)
            throw SceneError(where(t) + ": " + what + " needs a quoted name, found '" + quote(t.text) + "'");
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
            if (c.kind != Token::Close) throw SceneError(where(c) + ": " + what + ": expected ']'");
        } else {
            for (size_t k = 0; k < n; ++k) v.push_back(number(lex));
        }
        if (v.size() != n)
            throw SceneError(where(t) + ": " + what + " needs " + std::to_string(n) + " numbers, got " +
                             std::to_string(v.size()));
        return v;
    }

    ParamSet params(Lexer &lex, const Token &directive)
    {
        ParamSet ps;
        ps.where = where(directive);
        while (lex.peek().kind == Token::String) {
            Token decl = lex.next();
            std::istringstream in(decl.text);
            Param p;
            in >> p.type >> p.name;
            std::string extra;
            if (p.type.empty() || p.name.empty() || (in >> extra))
                throw SceneError(where(decl) + ": parameter \"" + quote(decl.text) + "\" is not \"type name\"");
            static const char *types[] = {"integer", "float",  "point2", "vector2", "point3", "vector3", "normal",
                                          "normal3", "point",  "vector", "rgb",     "string", "bool",    "texture",
                                          "spectrum", "blackbody"};
            bool known = false;
            for (const char *k : types) known |= p.type == k;
            if (!known) throw SceneError(where(decl) + ": unknown parameter type '" + quote(p.type) + "'");
            p.where = where(decl);
            bool textual = p.type == "string" || p.type == "bool" || p.type == "texture";
            auto take = [&](const Token &v) {
                if (v.kind == Token::Number) {
                    if (textual) throw SceneError(where(v) + ": '" + quote(p.name) + "' needs quoted values");
                    p.numbers.push_back(v.number);
                } else if (v.kind == Token::String) {
                    if (!textual && p.type != "spectrum")
                        throw SceneError(where(v) + ": '" + quote(p.name) + "' needs numbers, found \"" + quote(v.text) + "\"");
                    p.strings.push_back(v.text);
                } else if (v.kind == Token::Word && p.type == "bool" && (v.text == "true" || v.text == "false")) {
                    p.strings.push_back(v.text);
                } else {
                    throw SceneError(where(v) + ": bad value '" + quote(v.text) + "' for '" + quote(p.name) + "'");
                }
            };
            Token v = lex.next();
            if (v.kind == Token::Open) {
                while (lex.peek().kind != Token::Close) {
                    Token e = lex.next();
                    if (e.kind == Token::End) throw SceneError(where(e) + ": '" + quote(p.name) + "': missing ']'");
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
    // as pbrt-v4 resolves file names (resolve_path; pbrt-v4 tries the two in that order): the file's pairs replace its name.
    // Pairs are checked (an even count, increasing wavelengths).
    void resolve_spectrum(Param &p)
    {
        if (p.strings.size() > 1 || (p.strings.size() == 1 && !p.numbers.empty()))
            throw SceneError(p.where + ": '" + p.name + "' needs one spectrum: a name or (wavelength, value) pairs");
        if (p.strings.size() == 1 && !named_spectrum(p.strings[0])) {
            const std::string &file = p.strings[0];
            std::string full = resolve_path(scene_.search_dir, file);
            Spectrum s;
            try {
                s = read_spectrum_file(full);
            } catch (const SceneError &e) {
                if (pbrt_v4_named_spectrum(file))
                    throw SceneError(p.where + ": '" + p.name + "': \"" + file + "\" is one of pbrt-v4's named spectra, whose "
                                     "measured data udm1 does not hold (no maintained package it builds from provides "
                                     "them; it holds " + known_spectra() + ")");
                throw SceneError(p.where + ": '" + p.name + "': \"" + quote(file) + "\" is not a named spectrum that udm1 "
                                 "knows (" + known_spectra() + ") nor a spectrum file (" + e.what() + ")");
            }
            p.strings.clear();
            for (size_t i = 0; i < s.nm.size(); ++i) p.numbers.push_back(s.nm[i]), p.numbers.push_back(s.value[i]);
        }
        if (p.strings.empty()) spectrum_from_pairs(p.numbers, p.where + ": '" + p.name + "'");
    }

    // Refuses a parameter outside `allowed` (a geometry-only load ignores an appearance directive's). An
    // Attribute's default that this directive does not take is ignored, as pbrt-v4 ignores it, if udm1 takes it
    // for another directive of its kind (`kind`: what udm1 models for any), else refused: udm1 would not
    // know whether pbrt-v4 reads it here.
    void only(const ParamSet &ps, std::initializer_list<const char *> allowed, const std::string &what,
              bool appearance = false, const std::set<std::string> *kind = nullptr)
    {
        for (const Param &p : ps.params) {
            bool ok = false;
            for (const char *a : allowed) ok |= p.name == a;
            if (ok || (p.attribute && kind && kind->count(p.name))) continue;
            if (appearance && geometry_only_) ignore(p.where, what + " '" + p.name + "'");
            else if (p.attribute) throw SceneError(p.where + ": Attribute: parameter '" + p.name + "' is not modelled (" + what + ")");
            else throw SceneError(p.where + ": " + what + ": unsupported parameter '" + p.name + "'");
        }
    }

    // A directive's parameters with the Attribute defaults of its target appended (ParamSet::find takes
    // the directive's own first).
    ParamSet with_attributes(ParamSet ps, Target target) const
    {
        ps.params.insert(ps.params.end(), st_.attributes[target].begin(), st_.attributes[target].end());
        return ps;
    }

    // A file name as pbrt-v4 resolves it (resolve_path); one found nowhere is named where pbrt-v4 looks first,
    // in the main scene file's folder, for the message that it cannot be opened.
    std::string resolve(const std::string &file) const
    {
        std::string full = resolve_path(scene_.search_dir, file);
        struct stat st;
        if (full == file && !file.empty() && file[0] != '/' && !scene_.search_dir.empty() && stat(file.c_str(), &st) != 0)
            return scene_.search_dir + file;
        return full;
    }
    const std::string *name(const std::string &path)
    {
        names_.push_back(path);
        return &names_.back();
    }

    // pbrt-v4's transform directives change the transforms ActiveTransform made active.
    template <class F> void transform_active(F f)
    {
        for (int i = 0; i < 2; ++i)
            if (st_.active & (1 << i)) st_.ctm[i] = f(st_.ctm[i]);
    }
    void transform(const Mat4 &t)
    {
        transform_active([&](const Mat4 &m) { return m * t; });
    }
    static bool same(const Mat4 &a, const Mat4 &b)
    {
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 4; ++j)
                if (a.m[i][j] != b.m[i][j]) return false;
        return true;
    }
    // The transform of something placed by the current transforms (a shape, the camera, an instance): the
    // one in force while the shutter is open. pbrt-v4 moves it from the start transform (at the start of
    // TransformTimes) to the end one: motion blur, which udm1-pt does not model, is refused.
    const Mat4 &still(const std::string &here, const std::string &what) const
    {
        const Mat4 *m = st_.ctm;
        if (same(m[0], m[1]) || scene_.shutter_close <= transform_times_[0]) return m[0];
        if (scene_.shutter_open >= transform_times_[1]) return m[1];
        throw SceneError(here + ": " + what + " moves while the shutter is open (its ActiveTransform StartTime and "
                                              "EndTime transforms differ): motion blur is not modelled");
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
        params(lex, t);
        ignore(where(t), t.text);
    }


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
    // directive's "file:line".
    struct Call {
        Lexer &lex;
        const Token &t;
        const std::string &here;
    };
    using Handler = void (Parser::*)(const Call &);

    // Every directive of a token stream (a main or an imported file with its Includes).
    void run(Lexer &lex)
    {
        for (;;) {
            Token t = lex.next();
            if (t.kind == Token::End) break;
            if (t.kind != Token::Word)
                throw SceneError(where(t) + ": expected a directive, found '" + quote(t.text) + "'");
            directive(lex, t);
        }
    }

    void directive(Lexer &lex, const Token &t)
    {
        static const std::map<std::string, Handler> HANDLERS = {
            {"LookAt", &Parser::on_LookAt},
            {"Translate", &Parser::on_Translate},
            {"Scale", &Parser::on_Scale},
            {"Rotate", &Parser::on_Rotate},
            {"Transform", &Parser::on_Transform},
            {"ConcatTransform", &Parser::on_Transform},
            {"Identity", &Parser::on_Identity},
            {"CoordinateSystem", &Parser::on_CoordinateSystem},
            {"CoordSysTransform", &Parser::on_CoordSysTransform},
            {"ActiveTransform", &Parser::on_ActiveTransform},
            {"TransformTimes", &Parser::on_TransformTimes},
            {"Camera", &Parser::on_Camera},
            {"Film", &Parser::on_Film},
            {"Sampler", &Parser::on_Sampler},
            {"Accelerator", &Parser::on_Accelerator},
            {"Integrator", &Parser::on_Integrator},
            {"PixelFilter", &Parser::on_PixelFilter},
            {"ColorSpace", &Parser::on_ColorSpace},
            {"WorldBegin", &Parser::on_WorldBegin},
            {"AttributeBegin", &Parser::on_AttributeBegin},
            {"TransformBegin", &Parser::on_AttributeBegin},  // (pbrt-v4 reads TransformBegin/End as AttributeBegin/End)
            {"AttributeEnd", &Parser::on_AttributeEnd},
            {"TransformEnd", &Parser::on_AttributeEnd},
            {"Attribute", &Parser::on_Attribute},
            {"ReverseOrientation", &Parser::on_ReverseOrientation},
            {"Material", &Parser::on_Material},
            {"MakeNamedMaterial", &Parser::on_MakeNamedMaterial},
            {"NamedMaterial", &Parser::on_NamedMaterial},
            {"AreaLightSource", &Parser::on_AreaLightSource},
            {"LightSource", &Parser::on_LightSource},
            {"Shape", &Parser::on_Shape},
            {"ObjectBegin", &Parser::on_ObjectBegin},
            {"ObjectEnd", &Parser::on_ObjectEnd},
            {"ObjectInstance", &Parser::on_ObjectInstance},
            {"Include", &Parser::on_Include},
            {"Import", &Parser::on_Import},
            {"Texture", &Parser::on_Texture},
            {"MakeNamedMedium", &Parser::on_MakeNamedMedium},
            {"MediumInterface", &Parser::on_MediumInterface}};
        // what a geometry-only load (udm1-ao) skips: appearance, lights, media
        static const std::set<std::string> APPEARANCE = {"AreaLightSource", "LightSource", "Texture", "MakeNamedMedium",
                                                         "MediumInterface", "ColorSpace",  "Option"};
        // pbrt-v4's blocks: options before WorldBegin, the scene's description after it
        static const std::set<std::string> OPTIONS = {"Camera",      "Sampler",    "Film",       "PixelFilter",
                                                      "Accelerator", "Integrator", "WorldBegin", "TransformTimes"};
        static const std::set<std::string> WORLD = {
            "ReverseOrientation", "AttributeBegin",  "AttributeEnd",  "TransformBegin",    "TransformEnd",
            "LightSource",        "Shape",           "Texture",       "Material",          "MakeNamedMaterial",
            "NamedMaterial",      "AreaLightSource", "ObjectBegin",   "ObjectEnd",         "ObjectInstance",
            "Import"};
        const std::string here = where(t);
        if (in_world_ && OPTIONS.count(t.text))
            throw SceneError(here + ": " + t.text + " after WorldBegin: pbrt-v4 takes it only before");
        if (!in_world_ && WORLD.count(t.text))
            throw SceneError(here + ": " + t.text + " before WorldBegin: pbrt-v4 takes it only after");
        if (geometry_only_ && APPEARANCE.count(t.text)) return skip(lex, t);  // the emitters' shapes stay geometry
        auto it = HANDLERS.find(t.text);
        if (it == HANDLERS.end()) throw SceneError(here + ": unsupported directive '" + quote(t.text) + "'");
        (this->*it->second)(Call{lex, t, here});
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
        if (d == "Transform") transform_active([&](const Mat4 &) { return m; });
        else transform(m);
    }

    void on_Identity(const Call &)
    {
        transform_active([](const Mat4 &) { return Mat4(); });
    }

    // pbrt-v4's named coordinate systems: the transforms in force, saved by CoordinateSystem and put back by
    // CoordSysTransform; "camera" (the camera's world-from-camera, set by Camera) and "world" (identity, set
    // by WorldBegin) are predefined. An unknown name leaves the transform as it is, as pbrt-v4 does (with
    // a note).
    void on_CoordinateSystem(const Call &c)
    {
        std::string n = string_arg(c.lex, "CoordinateSystem");
        coordinate_systems_[n] = {st_.ctm[0], st_.ctm[1]};
    }

    void on_CoordSysTransform(const Call &c)
    {
        std::string n = string_arg(c.lex, "CoordSysTransform");
        auto it = coordinate_systems_.find(n);
        if (it == coordinate_systems_.end()) {
            scene_.notes.push_back(c.here + ": CoordSysTransform: no coordinate system \"" + quote(n) +
                                   "\" was named; the transform is left as it is, as pbrt-v4 leaves it");
            return;
        }
        st_.ctm[0] = it->second[0], st_.ctm[1] = it->second[1];
    }

    void on_ActiveTransform(const Call &c)
    {
        Token a = c.lex.next();
        if (a.kind == Token::Word && a.text == "All") st_.active = 3;
        else if (a.kind == Token::Word && a.text == "StartTime") st_.active = 1;
        else if (a.kind == Token::Word && a.text == "EndTime") st_.active = 2;
        else throw SceneError(where(a) + ": ActiveTransform takes All, StartTime or EndTime, not '" + quote(a.text) + "'");
    }

    void on_TransformTimes(const Call &c)
    {
        transform_times_[0] = number(c.lex), transform_times_[1] = number(c.lex);
        if (!(transform_times_[0] <= transform_times_[1]))
            throw SceneError(c.here + ": TransformTimes: the start time must not be after the end time");
    }

    void on_Camera(const Call &c)
    {
        Lexer &lex = c.lex;
        const Token &t = c.t;
        const std::string &here = c.here;
        std::string type = string_arg(lex, "Camera");
        ParamSet ps = params(lex, t);
        if (type != "perspective") throw SceneError(here + ": Camera \"" + type + "\" is not supported (perspective only)");
        only(ps, {"fov", "lensradius", "focaldistance", "shutteropen", "shutterclose"}, "Camera", true);
        scene_.camera.fov = ps.get_float("fov", 90);
        scene_.camera.lens_radius = ps.get_float("lensradius", 0);
        scene_.camera.focal_distance = ps.get_float("focaldistance", 1e6);
        if (!(scene_.camera.fov > 0 && scene_.camera.fov < 180)) throw SceneError(here + ": Camera fov outside (0, 180)");
        // the shutter: when time is sampled (motion, refused where it would show) and, as pbrt-v4's exposure
        // time, a factor of the image
        scene_.shutter_open = ps.get_float("shutteropen", 0), scene_.shutter_close = ps.get_float("shutterclose", 1);
        if (!(scene_.shutter_close - scene_.shutter_open > 0))
            throw SceneError(here + ": Camera: shutterclose must be after shutteropen (pbrt-v4 refuses a shutter that "
                                    "never opens)");
        if (ps.find("shutteropen") || ps.find("shutterclose")) shutter_where_ = here;
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
        Mat4 world_from_camera[2];
        for (int i = 0; i < 2; ++i) {
            if (!st_.ctm[i].affine()) throw SceneError(here + ": Camera: " + PROJECTIVE);
            if (!st_.ctm[i].inverse(&world_from_camera[i])) throw SceneError(here + ": Camera: singular transform");
        }
        coordinate_systems_["camera"] = {world_from_camera[0], world_from_camera[1]};
        still(here, "the camera");  // (the transforms in force are camera-from-world: the same test)
        scene_.camera.world_from_camera =
            same(st_.ctm[0], st_.ctm[1]) || scene_.shutter_close <= transform_times_[0] ? world_from_camera[0] : world_from_camera[1];
        camera_set_ = true;
        camera_media_ = {st_.outside, st_.media_where, here};  // pbrt-v4: the camera is in the outside medium
    }

    void on_Film(const Call &c)
    {
        Lexer &lex = c.lex;
        const Token &t = c.t;
        const std::string &here = c.here;
        std::string type = string_arg(lex, "Film");
        ParamSet ps = params(lex, t);
        if (type != "rgb" && type != "gbuffer") throw SceneError(here + ": Film \"" + type + "\" is not supported (rgb, gbuffer)");
        film_where_ = here;
        if (const Param *e = ps.find("exposuretime"))
            throw SceneError(e->where + ": Film: 'exposuretime' is not a parameter of pbrt-v4's film, which refuses it (the "
                                        "exposure time is the Camera's shutterclose - shutteropen)");
        if (const Param *e = ps.find("scale"))
            throw SceneError(e->where + ": Film: 'scale' is not a parameter of pbrt-v4's film, which refuses it as unused (its "
                                        "scale is the imaging ratio: iso and the Camera's shutter)");
        if (type == "gbuffer")
            only(ps, {"xresolution", "yresolution", "filename", "iso", "sensor", "whitebalance", "cropwindow", "pixelbounds",
                      "maxcomponentvalue", "savefp16", "diagonal", "coordinatesystem"}, "Film", true);
        else
            only(ps, {"xresolution", "yresolution", "filename", "iso", "sensor", "whitebalance", "cropwindow", "pixelbounds",
                      "maxcomponentvalue", "savefp16", "diagonal"}, "Film", true);
        // pbrt-v4's imaging ratio (exposure time x ISO / 100, made in finish()) scales the image; the sensor's
        // spectral response and white balance have no RGB counterpart: the film is a plain RGB sensor
        iso_ = ps.get_float("iso", 100.0);
        if (!(iso_ > 0 && iso_ < 1e8)) throw SceneError(ps.find("iso")->where + ": Film: iso must be positive");
        scene_.film_sensor = ps.get_string("sensor", "cie1931");
        scene_.width = ps.get_int("xresolution", 1280);
        scene_.height = ps.get_int("yresolution", 720);
        scene_.film_filename = ps.get_string("filename", "");
        if (scene_.width < 1 || scene_.height < 1 || scene_.width > 65536 || scene_.height > 65536)
            throw SceneError(here + ": Film resolution outside 1..65536");
        if (geometry_only_) {  // (udm1-ao renders the whole film, unclamped)
            for (const char *n : {"cropwindow", "pixelbounds", "maxcomponentvalue"})
                if (const Param *p = ps.find(n)) ignore(p->where, std::string("Film '") + n + "'");
            return;
        }
        film_sensor(ps);
        if (type == "gbuffer") {
            std::string cs = ps.get_string("coordinatesystem", "camera");
            if (cs != "camera" && cs != "world")
                throw SceneError(ps.find("coordinatesystem")->where + ": Film \"gbuffer\": coordinatesystem \"" + cs +
                                 "\" is not pbrt-v4's (camera, world)");
            scene_.notes.push_back(here + ": Film \"gbuffer\" renders as \"rgb\": its colour image, without the "
                                          "geometric buffers pbrt-v4 writes beside it");
        }
        if (const Param *p = ps.find("maxcomponentvalue", "float")) {
            scene_.max_component = ps.get_float("maxcomponentvalue", HUGE_VAL);
            if (!(scene_.max_component > 0))
                throw SceneError(p->where + ": Film: maxcomponentvalue must be positive");
        }
        // the part of the film rendered: pbrt-v4's rules (FilmBaseParameters), which it applies with a warning
        // where udm1-pt refuses (a list of the wrong length)
        if (const Param *p = ps.find("pixelbounds", "integer")) {
            if (p->numbers.size() != 4) throw SceneError(p->where + ": Film: pixelbounds needs 4 integers (x0 x1 y0 y1)");
            for (double v : p->numbers)
                if (!(std::fabs(v) < 1e9) || v != std::floor(v))
                    throw SceneError(p->where + ": Film: pixelbounds needs whole numbers");
            const std::vector<double> &b = p->numbers;  // (pbrt-v4's Bounds2i orders each pair)
            scene_.pixel_bounds[0] = (int)std::min(b[0], b[1]), scene_.pixel_bounds[1] = (int)std::max(b[0], b[1]);
            scene_.pixel_bounds[2] = (int)std::min(b[2], b[3]), scene_.pixel_bounds[3] = (int)std::max(b[2], b[3]);
            scene_.has_pixel_bounds = true;
        }
        if (const Param *p = ps.find("cropwindow", "float")) {
            if (p->numbers.size() != 4) throw SceneError(p->where + ": Film: cropwindow needs 4 numbers (x0 x1 y0 y1)");
            float v[4];
            for (int k = 0; k < 4; ++k) v[k] = (float)p->numbers[k];  // pbrt-v4 reads them as float
            auto clamp01 = [](float x) { return std::min(1.0f, std::max(0.0f, x)); };
            scene_.crop[0] = clamp01(std::min(v[0], v[1])), scene_.crop[1] = clamp01(std::max(v[0], v[1]));
            scene_.crop[2] = clamp01(std::min(v[2], v[3])), scene_.crop[3] = clamp01(std::max(v[2], v[3]));
            scene_.has_crop = true;
            if (scene_.has_pixel_bounds)
                scene_.notes.push_back(here + ": Film: both cropwindow and pixelbounds given: the cropwindow is used, as in "
                                              "pbrt-v4");
        }
        int window[4];
        try {
            scene_.film_window(scene_.width, scene_.height, window);
        } catch (const SceneError &) {
            throw SceneError(here + ": Film: the " + (scene_.has_crop ? "cropwindow" : "pixelbounds") +
                             " leaves no pixel of the film (pbrt-v4 refuses degenerate pixel bounds)");
        }
        if (ps.find("savefp16"))
            scene_.notes.push_back(ps.find("savefp16")->where + ": Film: savefp16 ignored: udm1-pt writes 32-bit floats "
                                                                "(and exact sums)");
    }

    // pbrt-v4's PixelSensor: "cie1931" (its default: the film records CIE XYZ) with an optional white balance
    // (white_balance.h). The cameras' sensors are measured spectral responses that no maintained package
    // provides: such a film renders as the cie1931 sensor with the white balance pbrt-v4 gives a camera (6500 K
    // unless the file says), with a note naming the sensor; a name pbrt-v4 does not know is refused.
    void film_sensor(const ParamSet &ps)
    {
        static const std::set<std::string> CAMERAS = {
            "canon_eos_100d", "canon_eos_1dx_mkii", "canon_eos_200d", "canon_eos_200d_mkii", "canon_eos_5d",
            "canon_eos_5d_mkii", "canon_eos_5d_mkiii", "canon_eos_5d_mkiv", "canon_eos_5ds", "canon_eos_m",
            "hasselblad_l1d_20c", "nikon_d810", "nikon_d850", "sony_ilce_6400", "sony_ilce_7m3", "sony_ilce_7rm3",
            "sony_ilce_9"};
        const std::string &sensor = scene_.film_sensor;
        const bool camera = sensor != "cie1931";
        if (camera && !CAMERAS.count(sensor))
            throw SceneError(ps.find("sensor")->where + ": Film: sensor \"" + quote(sensor) + "\" is not one of pbrt-v4's "
                                                        "(cie1931 and its cameras' names)");
        const Param *p = ps.find("whitebalance", "float");
        double kelvin = (float)ps.get_float("whitebalance", 0);  // (read as float, as pbrt-v4 reads it)
        if (!(kelvin >= 0) || !std::isfinite(kelvin))
            throw SceneError(p->where + ": Film: whitebalance must be a temperature in kelvin (0: none)");
        if (camera && kelvin == 0) kelvin = 6500;  // (pbrt-v4's default for a camera's sensor)
        Vec3 rows[3];
        if (kelvin > 0 && !white_balance_rgb(kelvin, rows))
            throw SceneError(p->where + ": Film: whitebalance " + number_text(kelvin) + " K: no light to balance to "
                                        "(Planck's law gives none at that temperature)");
        scene_.white_balance = kelvin;
        if (camera)
            scene_.notes.push_back(ps.find("sensor")->where + ": Film: sensor \"" + sensor + "\" (a camera's measured "
                                   "spectral response, which udm1 does not have) renders as the cie1931 sensor balanced "
                                   "from " + short_number(kelvin) + " K: its colours differ from pbrt-v4's by the "
                                   "camera's response");
    }

    void on_Sampler(const Call &c)
    {
        Lexer &lex = c.lex;
        const Token &t = c.t;
        const std::string &here = c.here;
        scene_.sampler = string_arg(lex, "Sampler");
        ParamSet ps = params(lex, t);
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
        params(lex, t);
        scene_.notes.push_back(here + ": Accelerator \"" + type + "\" ignored: rays are traced by Embree (the image does not depend on it)");
    }

    void on_Integrator(const Call &c)
    {
        Lexer &lex = c.lex;
        const Token &t = c.t;
        const std::string &here = c.here;
        scene_.integrator = string_arg(lex, "Integrator");
        ParamSet ps = params(lex, t);
        if (geometry_only_) {
            ignore(here, "Integrator");
        } else {  // udm1-pt is a unidirectional path tracer, with media for volpath
            const std::string &in = scene_.integrator;
            if (in != "path" && in != "volpath" && in != "simplepath" && in != "randomwalk" && in != "bdpt" && in != "sppm")
                throw SceneError(here + ": Integrator \"" + in + "\" is not supported (path, volpath; simplepath, "
                                        "randomwalk and sppm render as path, bdpt as volpath)");
            // pbrt-v3's Russian roulette threshold (scenes converted from pbrt-v3 keep it; pbrt-v4 refuses it as
            // unused): roulette changes the noise, not the image, which is rendered with pbrt-v4's roulette
            if (const Param *p = ps.find("rrthreshold")) {
                if (p->type != "float" || p->numbers.size() != 1)
                    throw SceneError(p->where + ": Integrator: rrthreshold takes one float");
                scene_.notes.push_back(p->where + ": Integrator: rrthreshold ignored: pbrt-v3's roulette threshold "
                                                  "(pbrt-v4 refuses it as unused); roulette changes the noise, not the image");
                ps.params.erase(ps.params.begin() + (p - ps.params.data()));
            }
            // each integrator's own parameters (pbrt-v4 refuses the others as unused)
            if (in == "path" || in == "volpath") only(ps, {"maxdepth", "lightsampler", "regularize"}, "Integrator \"" + in + "\"");
            else if (in == "simplepath") only(ps, {"maxdepth", "samplelights", "samplebsdf"}, "Integrator \"simplepath\"");
            else if (in == "bdpt") only(ps, {"maxdepth", "regularize", "visualizestrategies", "visualizeweights"}, "Integrator \"bdpt\"");
            else if (in == "sppm") only(ps, {"maxdepth", "photonsperiteration", "radius", "seed"}, "Integrator \"sppm\"");
            else only(ps, {"maxdepth"}, "Integrator \"randomwalk\"");
            for (const char *debug : {"visualizestrategies", "visualizeweights"})
                if (ps.get_bool(debug, false))
                    throw SceneError(ps.find(debug)->where + ": Integrator \"bdpt\": " + debug +
                                     " (pbrt-v4's images of its strategies) is not modelled");
            if (in == "sppm" && ps.find("radius") && !(ps.get_float("radius", 1) > 0))
                throw SceneError(ps.find("radius")->where + ": Integrator \"sppm\": radius must be positive");
            if (ps.get_bool("regularize", false))  // pbrt-v4 roughens near-specular BSDFs: a biased image
                scene_.notes.push_back(ps.find("regularize")->where + ": Integrator: regularize ignored: udm1-pt renders the "
                                                                      "unbiased image (pbrt-v4's regularized one is "
                                                                      "biased towards rougher specular paths)");
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
            if (in == "simplepath" || in == "randomwalk" || in == "bdpt" || in == "sppm") {  // the same image in the
                                                                                          // limit, found another way:
                // pbrt-v4's bdpt samples media as its volpath does; the others leave them out as its path does
                const std::string as = in == "bdpt" ? "volpath" : "path";
                scene_.notes.push_back(here + ": Integrator \"" + in + "\" renders as \"" + as + "\" (the unbiased image " +
                                       (in == "sppm" ? "sppm converges to" : "it converges to") + "; noise differs)");
                scene_.integrator = as;
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
        std::string type = string_arg(lex, "PixelFilter");
        ParamSet ps = params(lex, t);
        if (geometry_only_) {  // (udm1-ao's primary rays are its own: the pixel's centre or a box)
            ignore(c.here, "PixelFilter");
            return;
        }
        PixelFilter f;
        try {
            f = PixelFilter::defaults(type);
        } catch (const std::invalid_argument &) {
            throw SceneError(c.here + ": PixelFilter \"" + quote(type) + "\" is not one of pbrt-v4's filters (box, gaussian, "
                                      "mitchell, sinc, triangle)");
        }
        if (type == "gaussian") only(ps, {"xradius", "yradius", "sigma"}, "PixelFilter \"gaussian\"");
        else if (type == "mitchell") only(ps, {"xradius", "yradius", "B", "C"}, "PixelFilter \"mitchell\"");
        else if (type == "sinc") only(ps, {"xradius", "yradius", "tau"}, "PixelFilter \"sinc\"");
        else only(ps, {"xradius", "yradius"}, "PixelFilter \"" + type + "\"");
        // (pbrt-v4 reads them as float)
        f.xradius = (float)ps.get_float("xradius", f.xradius), f.yradius = (float)ps.get_float("yradius", f.yradius);
        f.sigma = (float)ps.get_float("sigma", f.sigma), f.tau = (float)ps.get_float("tau", f.tau);
        f.b = (float)ps.get_float("B", f.b), f.c = (float)ps.get_float("C", f.c);
        f.where = c.here;
        const char *at = "";
        std::string bad = f.invalid(&at);
        if (!bad.empty())
            throw SceneError((ps.find(at) ? ps.find(at)->where : c.here) + ": PixelFilter \"" + type + "\": " + bad);
        scene_.pixel_filter = f;
    }

    void on_ColorSpace(const Call &c)
    {
        std::string n = string_arg(c.lex, "ColorSpace");
        if (n != "srgb")
            throw SceneError(c.here + ": ColorSpace \"" + quote(n) + "\" is not modelled (srgb, pbrt-v4's default: udm1-pt renders "
                                      "in linear sRGB)");
        scene_.notes.push_back(c.here + ": ColorSpace \"srgb\": pbrt-v4's default, in which udm1-pt renders");
    }

    void on_WorldBegin(const Call &)
    {
        st_.ctm[0] = st_.ctm[1] = Mat4();  // (pbrt-v4 keeps the rest of the state)
        st_.active = 3;
        coordinate_systems_["world"] = {Mat4(), Mat4()};
        in_world_ = true;
    }

    void on_AttributeBegin(const Call &c)
    {
        stack_.push_back(st_);
        blocks_.emplace_back('a', c.here);
    }

    void on_AttributeEnd(const Call &c)
    {
        const std::string &d = c.t.text;
        const std::string &here = c.here;
        if (stack_.size() <= import_floor_) throw SceneError(here + ": " + d + " without a matching begin");
        if (blocks_.back().first == 'o')
            throw SceneError(here + ": " + d + " ends the ObjectBegin of " + blocks_.back().second + " (pbrt-v4 refuses "
                                                                                                     "mismatched nesting)");
        st_ = stack_.back();
        stack_.pop_back(), blocks_.pop_back();
    }

    // Attribute "shape" | "light" | "material" | "medium" | "texture" params: defaults for the later directives
    // of that kind in the block (pbrt-v4's graphics state), which their own parameters override.
    void on_Attribute(const Call &c)
    {
        std::string target = string_arg(c.lex, "Attribute");
        ParamSet ps = params(c.lex, c.t);
        int k = 0;
        while (k < TARGETS && target != TARGET_NAMES[k]) ++k;
        if (k == TARGETS)
            throw SceneError(c.here + ": Attribute \"" + quote(target) + "\": the target must be shape, light, material, medium or "
                                      "texture");
        for (Param &p : ps.params) p.attribute = true, st_.attributes[k].push_back(p);
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
        m.params = with_attributes(params(lex, t), MATERIAL);
        resolve_material_files(&m.params);
        tabulated_material(c.here, &m);
        scene_.materials.push_back(m);
        st_.material = (int)scene_.materials.size() - 1;
        st_.named_material.clear();
    }

    void on_MakeNamedMaterial(const Call &c)
    {
        Lexer &lex = c.lex;
        const Token &t = c.t;
        const std::string &here = c.here;
        std::string name = string_arg(lex, "MakeNamedMaterial");
        Material m;
        m.params = with_attributes(params(lex, t), MATERIAL);
        resolve_material_files(&m.params);
        m.name = name;
        m.type = m.params.get_string("type", "");
        if (m.type.empty()) throw SceneError(here + ": MakeNamedMaterial \"" + name + "\" has no \"string type\"");
        tabulated_material(here, &m);
        auto it = named_.find(name);
        if (it != named_.end())
            throw SceneError(here + ": MakeNamedMaterial \"" + quote(name) + "\" was already made at " + it->second.where +
                             " (pbrt-v4 refuses a redefinition)");
        scene_.materials.push_back(m);
        named_[name] = {(int)scene_.materials.size() - 1, here};
    }

    // A material's file names (its "normalmap") resolved by pbrt-v4's path rule (resolve).
    void resolve_material_files(ParamSet *ps) const
    {
        for (Param &p : ps->params)
            if (p.name == "normalmap" && p.type == "string" && p.strings.size() == 1 && !p.strings[0].empty())
                p.strings[0] = resolve(p.strings[0]);
    }

    // Material "measured": its "string filename" (pbrt-v4 needs one) found by pbrt-v4's path rule (resolve) and
    // read (tabulated_bsdf.h), once per file as pbrt-v4 reads it; a file it cannot read is one line naming it.
    void tabulated_material(const std::string &here, Material *m)
    {
        if (m->type != "measured") return;
        Param *file = nullptr;
        for (Param &p : m->params.params)
            if (p.name == "filename" && !file) file = &p;
        if (!file || file->type != "string" || file->strings.size() != 1 || file->strings[0].empty())
            throw SceneError((file ? file->where : here) + ": Material \"measured\": no \"string filename\" (pbrt-v4 needs "
                                                          "the tabulated BSDF file)");
        const std::string name = file->strings[0], path = resolve(name);
        file->strings[0] = path;
        auto it = tabulated_.find(path);
        if (it != tabulated_.end()) {
            m->tabulated = it->second;
            return;
        }
        try {
            m->tabulated = read_tabulated_bsdf(path);
        } catch (const SceneError &e) {
            throw SceneError(file->where + ": Material \"measured\": " + e.what() + where_looked(name, path));
        }
        tabulated_[path] = m->tabulated;
    }

    // The name is looked up when the scene is complete (finish()), as pbrt-v4 does when it creates the scene:
    // a MakeNamedMaterial after the shapes that use it (in the file or in a later Include) is found.
    void on_NamedMaterial(const Call &c)
    {
        st_.named_material = string_arg(c.lex, "NamedMaterial");
        st_.named_where = c.here;
        st_.material = -1;
    }

    void on_AreaLightSource(const Call &c)
    {
        Lexer &lex = c.lex;
        const Token &t = c.t;
        const std::string &here = c.here;
        std::string type = string_arg(lex, "AreaLightSource");
        ParamSet ps = with_attributes(params(lex, t), LIGHT);
        if (type != "diffuse") throw SceneError(here + ": AreaLightSource \"" + type + "\" is not supported (diffuse only)");
        only(ps, {"L", "scale", "twosided"}, "AreaLightSource", false, &LIGHT_PARAMETERS);
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
        light_source(c.lex, c.t);
    }

    void on_Shape(const Call &c)
    {
        shape(c.lex, c.t);
    }

    // pbrt-v4's Include: the file's tokens come next in the same stream (Lexer), its name resolved against
    // the main scene file's folder; a name ending in .gz is inflated.
    void on_Include(const Call &c)
    {
        Lexer &lex = c.lex;
        const std::string &d = c.t.text;
        std::string file = string_arg(lex, d), full = resolve(file), text;
        if (lex.depth() > 32) throw SceneError(c.here + ": Include nested too deeply (" + file + ")");
        try {
            text = read_scene_file(full, "scene file");
        } catch (const SceneError &e) {
            throw SceneError(c.here + ": " + d + ": " + e.what() + where_looked(file, full));
        }
        lex.push(std::move(text), name(full));
    }

    // pbrt-v4's Import (the world block only): the file is read as a stream of its own, with a copy of the
    // graphics state; what it defines (shapes, instances, named materials, textures, media) joins the
    // scene, and the state it changes (transforms, material, attributes, named coordinate systems) stays in
    // it. An ObjectBegin open at the Import takes the file's shapes.
    void on_Import(const Call &c)
    {
        std::string file = string_arg(c.lex, "Import"), full = resolve(file), text;
        if (import_depth_ > 32) throw SceneError(c.here + ": Import nested too deeply (" + file + ")");
        try {
            text = read_scene_file(full, "scene file");
        } catch (const SceneError &e) {
            throw SceneError(c.here + ": Import: " + e.what() + where_looked(file, full));
        }
        State saved = st_;
        auto saved_systems = coordinate_systems_;
        size_t saved_floor = import_floor_, saved_object_floor = object_floor_;
        import_floor_ = stack_.size();
        object_floor_ = current_object_ >= 0 ? 1 : 0;  // an object open outside: its ObjectEnd is outside too
        coordinate_systems_.clear();                   // (pbrt-v4's imported file starts with none named)
        ++import_depth_;
        Lexer imported;
        imported.push(std::move(text), name(full));
        run(imported);
        --import_depth_;
        if (stack_.size() > import_floor_)
            throw SceneError(blocks_.back().second + ": " + (blocks_.back().first == 'o' ? "ObjectBegin" : "AttributeBegin") +
                             " is never ended in its imported file");
        st_ = saved;
        coordinate_systems_ = saved_systems;
        import_floor_ = saved_floor, object_floor_ = saved_object_floor;
    }

    // Where pbrt-v4 looks for a relative file name that could not be read: the main scene file's folder, then
    // the working directory.
    std::string where_looked(const std::string &file, const std::string &full) const
    {
        struct stat st;
        if (file.empty() || file[0] == '/' || scene_.search_dir.empty() || stat(full.c_str(), &st) == 0) return "";
        return " (pbrt-v4 looks for \"" + file + "\" in " + scene_.search_dir + ", the main scene file's folder, for "
               "names in included files too, then in the working directory)";
    }

    // ObjectBegin "name" ... ObjectEnd: the shapes between them make an object (pbrt-v4 pushes the graphics
    // state as AttributeBegin does), placed by each ObjectInstance of its name.
    void on_ObjectBegin(const Call &c)
    {
        std::string n = string_arg(c.lex, "ObjectBegin");
        if (current_object_ >= 0)
            throw SceneError(c.here + ": ObjectBegin inside the ObjectBegin of " + scene_.objects[current_object_].where +
                             " (pbrt-v4 refuses it)");
        auto it = object_index_.find(n);
        if (it != object_index_.end())
            throw SceneError(c.here + ": ObjectBegin \"" + quote(n) + "\": the object was already made at " +
                             scene_.objects[it->second].where + " (pbrt-v4 refuses a redefinition)");
        stack_.push_back(st_);
        blocks_.emplace_back('o', c.here);
        scene_.objects.push_back({n, c.here});
        current_object_ = (int)scene_.objects.size() - 1;
        object_index_[n] = current_object_;
    }

    void on_ObjectEnd(const Call &c)
    {
        if (current_object_ < 0) throw SceneError(c.here + ": ObjectEnd without an ObjectBegin");
        if (object_floor_ > 0 && import_depth_ > 0)
            throw SceneError(c.here + ": ObjectEnd in an imported file for the ObjectBegin of " +
                             scene_.objects[current_object_].where + " outside it (pbrt-v4 refuses it)");
        if (blocks_.back().first != 'o')
            throw SceneError(c.here + ": ObjectEnd while the AttributeBegin of " + blocks_.back().second +
                             " is open (pbrt-v4 refuses mismatched nesting)");
        st_ = stack_.back();
        stack_.pop_back(), blocks_.pop_back();
        current_object_ = -1;
    }

    // Resolved after parsing (resolve_instances), as pbrt-v4 resolves it: the object may be made later.
    void on_ObjectInstance(const Call &c)
    {
        std::string n = string_arg(c.lex, "ObjectInstance");
        if (current_object_ >= 0)
            throw SceneError(c.here + ": ObjectInstance inside the ObjectBegin of " + scene_.objects[current_object_].where +
                             " (pbrt-v4 refuses it)");
        pending_instances_.push_back({n, still(c.here, "the instance"), c.here});
    }

    void on_Texture(const Call &c)
    {
        Lexer &lex = c.lex;
        const Token &t = c.t;
        const std::string &d = c.t.text;
        const std::string &here = c.here;
        Texture tx;
        tx.name = string_arg(lex, d), tx.kind = string_arg(lex, d), tx.type = string_arg(lex, d);
        ParamSet ps = with_attributes(params(lex, t), TEXTURE);
        tx.where = here;
        if (tx.kind != "float" && tx.kind != "spectrum")
            throw SceneError(here + ": Texture \"" + tx.name + "\": kind \"" + tx.kind + "\" is not float or spectrum");
        auto old = textures_.find({tx.kind, tx.name});
        if (old != textures_.end())
            throw SceneError(here + ": Texture \"" + quote(tx.name) + "\": a " + tx.kind + " texture of that name was already made at " +
                             scene_.textures[old->second].where + " (pbrt-v4 refuses a redefinition)");
        bool first_of_file = false;  // an image texture pbrt-v4 reads before any other texture (see resolve_textures)
        std::vector<std::string> used;  // the parameters this texture reads (pbrt-v4 refuses the others)
        if (tx.type == "imagemap") {
            used = {"filename", "encoding", "invert", "scale", "wrap", "filter", "maxanisotropy"};
            std::string file = ps.get_string("filename", "");
            if (file.empty()) throw SceneError(here + ": Texture imagemap needs \"string filename\"");
            tx.filename = resolve(file);
            first_of_file = image_files_.insert(tx.filename).second;
            // pbrt-v4's default encoding: sRGB for .png files, linear for the others
            std::string ext = file.size() >= 4 ? file.substr(file.size() - 4) : "";
            std::transform(ext.begin(), ext.end(), ext.begin(), ::tolower);
            std::string enc = ps.get_string("encoding", ext == ".png" ? "sRGB" : "linear");
            if (enc != "sRGB" && enc != "linear")
                throw SceneError(here + ": Texture imagemap: encoding \"" + enc + "\" is not supported (sRGB, linear)");
            tx.srgb = enc == "sRGB";
            tx.invert = ps.get_bool("invert", false);
            tx.scale = ps.get_float("scale", 1.0);
            tx.wrap = ps.get_string("wrap", "repeat");
            if (tx.wrap != "repeat" && tx.wrap != "clamp" && tx.wrap != "black")
                throw SceneError(here + ": Texture imagemap: wrap \"" + tx.wrap + "\" is not supported (repeat, clamp, black)");
            // the filters: udm1-pt traces no ray differentials, so pbrt-v4's footprint filters (trilinear, EWA)
            // see the finest level, bilinear, as its own "bilinear" filter does for a footprint below a texel
            std::string filter = ps.get_string("filter", "bilinear");
            if (filter != "bilinear" && filter != "point" && filter != "trilinear" && filter != "ewa" && filter != "EWA")
                throw SceneError(here + ": Texture imagemap: filter \"" + filter + "\" is not one of pbrt-v4's (point, "
                                        "bilinear, trilinear, ewa)");
            tx.point = filter == "point";
            double aniso = ps.get_float("maxanisotropy", 8.0);  // (it shapes pbrt-v4's EWA footprint only)
            if (!(aniso > 0)) throw SceneError(ps.find("maxanisotropy")->where + ": Texture imagemap: maxanisotropy must be positive");
            texture_mapping(ps, here, &tx.mapping, &used);
        } else if (tx.type == "constant") {
            used = {"value"};
            tx.tex1 = texture_constant(ps, "value", tx.kind, 1.0, false);
        } else if (tx.type == "scale") {
            used = {"tex", "scale"};
            tx.tex1 = texture_input(ps, "tex", tx.kind, 1.0, &Texture::tex1);
            tx.tex2 = texture_input(ps, "scale", "float", 1.0, &Texture::tex2);
        } else if (tx.type == "mix") {
            used = {"tex1", "tex2", "amount"};
            tx.tex1 = texture_input(ps, "tex1", tx.kind, 0.0, &Texture::tex1);
            tx.tex2 = texture_input(ps, "tex2", tx.kind, 1.0, &Texture::tex2);
            tx.amount = texture_input(ps, "amount", "float", 0.5, &Texture::amount);
        } else if (tx.type == "directionmix") {
            used = {"tex1", "tex2", "dir"};
            tx.tex1 = texture_input(ps, "tex1", tx.kind, 0.0, &Texture::tex1);
            tx.tex2 = texture_input(ps, "tex2", tx.kind, 1.0, &Texture::tex2);
            const Param *dp = ps.find("dir", "vector3");
            Vec3 v(0, 1, 0);
            if (dp) {
                if (dp->numbers.size() != 3) throw SceneError(dp->where + ": 'dir' needs 3 numbers");
                v = Vec3(dp->numbers[0], dp->numbers[1], dp->numbers[2]);
            }
            v = st_.ctm[0].vector(v);  // (to world space: pbrt-v4's renderFromTexture, its start transform)
            if (!(length(v) > 0)) throw SceneError(here + ": Texture directionmix: dir is zero");
            tx.dir = normalize(v);
        } else if (tx.type == "checkerboard") {
            used = {"tex1", "tex2", "dimension"};
            tx.tex1 = texture_input(ps, "tex1", tx.kind, 1.0, &Texture::tex1);
            tx.tex2 = texture_input(ps, "tex2", tx.kind, 0.0, &Texture::tex2);
            tx.dimension = ps.get_int("dimension", 2);
            if (tx.dimension != 2 && tx.dimension != 3)
                throw SceneError(ps.find("dimension")->where + ": Texture checkerboard: dimension must be 2 or 3");
            if (tx.dimension == 2) texture_mapping(ps, here, &tx.mapping, &used);
            else if (!st_.ctm[0].affine() || !st_.ctm[0].inverse(&tx.mapping.texture_from_world))
                throw SceneError(here + ": Texture checkerboard: its transform is singular or projective");
        } else if (tx.type == "fbm" || tx.type == "wrinkled" || tx.type == "windy") {
            if (tx.kind != "float")
                throw SceneError(here + ": Texture \"" + tx.type + "\" is a float texture in pbrt-v4, not a " + tx.kind + " texture");
            if (tx.type != "windy") {
                used = {"octaves", "roughness"};
                tx.octaves = ps.get_int("octaves", 8);
                tx.omega = ps.get_float("roughness", 0.5);
                if (tx.octaves < 0 || tx.octaves > 64)
                    throw SceneError(ps.find("octaves")->where + ": Texture " + tx.type + ": octaves must be in [0, 64]");
                if (!std::isfinite(tx.omega))
                    throw SceneError(ps.find("roughness")->where + ": Texture " + tx.type + ": roughness must be finite");
            }
            if (!st_.ctm[0].affine() || !st_.ctm[0].inverse(&tx.mapping.texture_from_world))
                throw SceneError(here + ": Texture " + tx.type + ": its transform is singular or projective");
            if (!noise_texture_noted_) {
                noise_texture_noted_ = true;
                scene_.notes.push_back(here + ": Texture \"" + tx.type + "\": udm1-pt traces no ray differentials, so its "
                                       "noise sums every octave, where pbrt-v4 puts the average of those finer than a "
                                       "pixel's footprint");
            }
        } else {
            throw SceneError(here + ": Texture \"" + tx.type + "\" is not supported (imagemap, constant, scale, mix, "
                                    "directionmix, checkerboard, fbm, wrinkled, windy)");
        }
        for (const Param &p : ps.params)
            if (std::find(used.begin(), used.end(), p.name) == used.end()) {
                if (p.attribute && TEXTURE_PARAMETERS.count(p.name)) continue;  // (an Attribute default: as only())
                if (p.attribute) throw SceneError(p.where + ": Attribute: parameter '" + p.name + "' is not modelled (Texture " + tx.type + ")");
                throw SceneError(p.where + ": Texture " + tx.type + ": unsupported parameter '" + p.name + "'");
            }
        scene_.textures.push_back(tx);
        textures_[{tx.kind, tx.name}] = (int)scene_.textures.size() - 1;
        image_first_.push_back(first_of_file);
    }

    // A 2D texture's mapping (pbrt-v4's TextureMapping2D::Create): "mapping" and the parameters of that
    // mapping, added to *used; the others are refused as pbrt-v4 refuses unused parameters.
    void texture_mapping(const ParamSet &ps, const std::string &here, TextureMapping *m, std::vector<std::string> *used)
    {
        std::string kind = ps.get_string("mapping", "uv");
        used->push_back("mapping");
        if (kind == "uv") {
            m->kind = TextureMapping::UV;
            m->su = ps.get_float("uscale", 1.0), m->sv = ps.get_float("vscale", 1.0);
            m->du = ps.get_float("udelta", 0.0), m->dv = ps.get_float("vdelta", 0.0);
            used->insert(used->end(), {"uscale", "vscale", "udelta", "vdelta"});
        } else if (kind == "spherical" || kind == "cylindrical" || kind == "planar") {
            m->kind = kind == "spherical" ? TextureMapping::Spherical
                      : kind == "cylindrical" ? TextureMapping::Cylindrical
                                              : TextureMapping::Planar;
            if (!st_.ctm[0].affine() || !st_.ctm[0].inverse(&m->texture_from_world))
                throw SceneError(here + ": Texture mapping \"" + kind + "\": its transform is singular or projective");
            if (kind == "planar") {
                auto vec = [&](const char *name, Vec3 fallback) {
                    const Param *p = ps.find(name, "vector3");
                    if (!p) return fallback;
                    if (p->numbers.size() != 3) throw SceneError(p->where + ": '" + name + "' needs 3 numbers");
                    return Vec3(p->numbers[0], p->numbers[1], p->numbers[2]);
                };
                m->v1 = vec("v1", Vec3(1, 0, 0)), m->v2 = vec("v2", Vec3(0, 1, 0));
                m->du = ps.get_float("udelta", 0.0), m->dv = ps.get_float("vdelta", 0.0);
                used->insert(used->end(), {"v1", "v2", "udelta", "vdelta"});
            }
        } else {
            throw SceneError(ps.find("mapping")->where + ": Texture mapping \"" + kind +
                             "\" is not one of pbrt-v4's (uv, spherical, cylindrical, planar)");
        }
        for (double x : {m->su, m->sv, m->du, m->dv, m->v1.x, m->v1.y, m->v1.z, m->v2.x, m->v2.y, m->v2.z})
            if (!std::isfinite(x)) throw SceneError(here + ": Texture mapping: a parameter is not finite");
    }

    // A texture's constant parameter of its kind: "float" for a float texture; "rgb" or "spectrum" for a
    // spectrum texture, as an albedo (RGB components in [0, 1], as pbrt-v4 requires of albedos; a spectrum by
    // its RGB under D65, clamped per wavelength).
    TextureInput texture_constant(const ParamSet &ps, const std::string &name, const std::string &kind, double fallback,
                                  bool texture_allowed)
    {
        TextureInput in;
        in.value = fallback, in.rgb = Vec3(fallback, fallback, fallback);
        const Param *p = ps.find(name);
        if (!p) return in;
        if (kind == "float") {
            if (p->type != "float" || p->numbers.size() != 1)
                throw SceneError(p->where + ": '" + name + "' must be \"float " + name + "\"" +
                                 (texture_allowed ? " or \"texture " + name + "\"" : std::string()));
            in.value = p->numbers[0];
            if (!std::isfinite(in.value)) throw SceneError(p->where + ": '" + name + "' is not finite");
            return in;
        }
        if (p->type == "rgb") {
            if (p->numbers.size() != 3) throw SceneError(p->where + ": '" + name + "' needs 3 numbers");
            in.rgb = Vec3(p->numbers[0], p->numbers[1], p->numbers[2]);
            for (int k = 0; k < 3; ++k)
                if (!(in.rgb[k] >= 0 && in.rgb[k] <= 1))
                    throw SceneError(p->where + ": RGB parameter '" + name + "' of a spectrum texture is an albedo and "
                                                "must be in [0, 1], as pbrt-v4 requires");
            return in;
        }
        if (p->type == "spectrum") {
            const Spectrum *named = p->strings.size() == 1 ? named_spectrum(p->strings[0]) : nullptr;
            in.rgb = albedo_rgb(named ? *named : spectrum_from_pairs(p->numbers, p->where));
            return in;
        }
        throw SceneError(p->where + ": '" + name + "' must be an rgb, a spectrum" +
                         (texture_allowed ? std::string(" or a texture") : std::string()));
    }

    // A texture-valued parameter of the texture being made: "texture NAME" (a texture of that kind, found
    // when the scene is complete: resolve_textures), or a constant (texture_constant).
    TextureInput texture_input(const ParamSet &ps, const std::string &name, const std::string &kind, double fallback,
                               TextureInput Texture::*input)
    {
        const Param *p = ps.find(name);
        if (!p || p->type != "texture") return texture_constant(ps, name, kind, fallback, true);
        if (p->strings.size() != 1) throw SceneError(p->where + ": '" + name + "' needs one texture name");
        pending_textures_.push_back({scene_.textures.size(), input, kind, p->strings[0], p->where});
        return TextureInput();
    }

    // MakeNamedMedium: pbrt-v4's "homogeneous", "uniformgrid", "cloud" and "nanovdb" media with its parameters and
    // defaults (sigma_a and sigma_s 1, scale 1, g 0, no emission; a homogeneous medium's preset in place of
    // sigma_a and sigma_s), in linear sRGB; a grid medium placed by the transform in force. pbrt-v4's "rgbgrid" is
    // recorded by name: refused where Integrator "volpath" renders a shape or the camera in one.
    void on_MakeNamedMedium(const Call &c)
    {
        Lexer &lex = c.lex;
        const Token &t = c.t;
        const std::string &d = c.t.text;
        const std::string &here = c.here;
        std::string name = string_arg(lex, d);
        ParamSet ps = with_attributes(params(lex, t), MEDIUM);
        if (media_.count(name)) throw SceneError(here + ": MakeNamedMedium \"" + quote(name) + "\" is made twice (pbrt-v4 refuses it)");
        std::string type = ps.get_string("type", "");
        if (type.empty()) throw SceneError(here + ": MakeNamedMedium \"" + name + "\" has no \"string type\"");
        if (scene_.media_where.empty()) scene_.media_where = here;
        if (type == "rgbgrid") {
            media_[name] = {-1, type, here};
            return;
        }
        if (type != "homogeneous" && type != "uniformgrid" && type != "cloud" && type != "nanovdb")
            throw SceneError(here + ": MakeNamedMedium \"" + name + "\": type \"" + type +
                             "\" is not supported (homogeneous, uniformgrid, cloud and nanovdb; pbrt-v4's rgbgrid is not "
                             "modelled)");
        Medium m;
        m.name = name, m.where = here;
        m.sigma_a = m.sigma_s = Vec3(1, 1, 1);
        if (type == "homogeneous") {
            only(ps, {"type", "sigma_a", "sigma_s", "scale", "g", "Le", "Lescale", "preset"}, "MakeNamedMedium");
        } else if (type == "uniformgrid") {
            only(ps, {"type", "sigma_a", "sigma_s", "scale", "g", "Le", "Lescale", "density", "temperature", "nx", "ny", "nz",
                      "p0", "p1", "temperatureoffset", "temperaturecutoff", "temperaturescale"},
                 "MakeNamedMedium \"" + type + "\"");
            m.kind = Medium::UniformGrid;
        } else if (type == "nanovdb") {
            only(ps, {"type", "sigma_a", "sigma_s", "scale", "g", "filename", "gridname", "temperaturename", "Lescale",
                      "temperatureoffset", "temperaturecutoff", "temperaturescale"},
                 "MakeNamedMedium \"" + type + "\"");
            m.kind = Medium::NanoVDB;
        } else {
            only(ps, {"type", "sigma_a", "sigma_s", "g", "density", "wispiness", "frequency", "p0", "p1"},
                 "MakeNamedMedium \"" + type + "\"");
            m.kind = Medium::Cloud;
        }
        bool preset = false;
        if (const Param *p = m.kind == Medium::Homogeneous ? ps.find("preset", "string") : nullptr) {
            std::string which = ps.get_string("preset", "");
            preset = medium_preset(which, &m.sigma_a, &m.sigma_s);
            if (!preset)  // pbrt-v4 warns and takes sigma_a and sigma_s from the parameters
                scene_.notes.push_back(p->where + ": MakeNamedMedium \"" + name + "\": preset \"" + which +
                                       "\" is not one of pbrt-v4's (" + medium_preset_names() +
                                       "): sigma_a and sigma_s are the parameters' (default 1), as pbrt-v4 takes them");
        }
        for (const char *k : {"sigma_a", "sigma_s"}) {
            const Param *p = ps.find(k);
            if (!p) continue;
            if (preset && p->attribute) continue;  // (an Attribute default: pbrt-v4 never calls it unused)
            if (preset)
                throw SceneError(p->where + ": MakeNamedMedium \"" + name + "\": '" + k +
                                 "' with a preset: pbrt-v4 takes the preset's and refuses '" + k + "' as unused");
            (k[6] == 'a' ? m.sigma_a : m.sigma_s) = coefficient(*p, "MakeNamedMedium");
        }
        if (m.kind != Medium::Cloud) {  // (pbrt-v4's cloud has no scale)
            double scale = ps.get_float("scale", 1.0);
            if (!(scale >= 0)) throw SceneError(ps.find("scale")->where + ": MakeNamedMedium: scale must not be negative");
            m.sigma_a = m.sigma_a * scale, m.sigma_s = m.sigma_s * scale;
        }
        m.g = ps.get_float("g", 0.0);
        if (m.kind == Medium::Homogeneous) {
            double le_scale = ps.get_float("Lescale", 1.0);
            if (ps.find("Le")) m.Le = emission(ps, "Le", "MakeNamedMedium") * le_scale;
            if (!(le_scale >= 0)) throw SceneError(ps.find("Lescale")->where + ": MakeNamedMedium: Lescale must not be negative");
        } else {
            grid_medium(ps, &m);
        }
        media_[name] = {(int)scene_.media.size(), type, here};
        scene_.media.push_back(std::move(m));
    }

    // A grid medium's own parameters (MakeNamedMedium "uniformgrid" or "cloud"), checked as pbrt-v4 checks them
    // and more: its box, the transform in force, the uniform grid's values.
    void grid_medium(const ParamSet &ps, Medium *m)
    {
        const std::string what = "MakeNamedMedium \"" + m->name + "\"";
        Vec3 a = ps.get_point("p0", Vec3(0, 0, 0)), b = ps.get_point("p1", Vec3(1, 1, 1));
        m->p0 = Vec3(std::min(a.x, b.x), std::min(a.y, b.y), std::min(a.z, b.z));  // (pbrt-v4's Bounds3f of the two)
        m->p1 = Vec3(std::max(a.x, b.x), std::max(a.y, b.y), std::max(a.z, b.z));
        for (int k = 0; k < 3; ++k)
            if (!(m->p1[k] > m->p0[k]) || !std::isfinite(m->p1[k] - m->p0[k]))
                throw SceneError((ps.find("p0") ? ps.find("p0") : ps.find("p1") ? ps.find("p1") : &ps.params[0])->where +
                                 ": " + what + ": the box p0 p1 is empty along an axis");
        if (!st_.ctm[0].affine() || !st_.ctm[0].inverse(&m->medium_from_world))
            throw SceneError(m->where + ": " + what + ": the transform in force is singular or projective");
        if (!same(st_.ctm[0], st_.ctm[1]))  // pbrt-v4 warns and takes the start transform
            scene_.notes.push_back(m->where + ": " + what + ": an animated transform; the medium takes the start "
                                   "transform, as pbrt-v4 takes it");
        if (m->kind == Medium::NanoVDB) return nanovdb_medium(ps, m);
        if (m->kind == Medium::Cloud) {
            m->cloud_density = ps.get_float("density", 1.0);
            m->wispiness = ps.get_float("wispiness", 1.0);
            m->frequency = ps.get_float("frequency", 5.0);
            for (const char *k : {"density", "wispiness", "frequency"})
                if (const Param *p = ps.find(k); p && !std::isfinite(ps.get_float(k, 0)))
                    throw SceneError(p->where + ": " + what + ": '" + k + "' must be finite");
            return;
        }
        int n[3];
        const char *axes[3] = {"nx", "ny", "nz"};
        for (int k = 0; k < 3; ++k) {
            n[k] = ps.get_int(axes[k], 1);
            if (n[k] < 1) throw SceneError(ps.find(axes[k])->where + ": " + what + ": '" + axes[k] + "' must be at least 1");
        }
        m->nx = n[0], m->ny = n[1], m->nz = n[2];
        const uint64_t count = (uint64_t)n[0] * (uint64_t)n[1] * (uint64_t)n[2];
        const std::string expect = std::to_string(n[0]) + " x " + std::to_string(n[1]) + " x " + std::to_string(n[2]) +
                                   " = " + std::to_string(count);
        // a grid of floats: count values, each finite and, but for temperatures, not negative
        auto grid = [&](const char *k, bool negative_ok, std::vector<float> *out) -> const Param * {
            const Param *p = ps.find(k, "float");
            if (!p) return nullptr;
            if (p->numbers.size() != count)
                throw SceneError(p->where + ": " + what + ": '" + k + "' has " + std::to_string(p->numbers.size()) +
                                 " values; nx ny nz need " + expect);
            out->resize(count);
            for (size_t i = 0; i < count; ++i) {
                double v = p->numbers[i];
                if (!std::isfinite(v) || (!negative_ok && v < 0) || std::fabs(v) > 3.4e38)
                    throw SceneError(p->where + ": " + what + ": '" + k + "' value " + std::to_string(i) + " (" + std::to_string(v) +
                                     ") must be " + (negative_ok ? "finite" : "finite and not negative"));
                (*out)[i] = (float)v;
            }
            return p;
        };
        if (!grid("density", false, &m->density))
            throw SceneError(m->where + ": " + what + ": no \"float density\" values (pbrt-v4 needs them)");
        const Param *temperature = grid("temperature", true, &m->temperature);
        if (ps.find("Le") && temperature)
            throw SceneError(temperature->where + ": " + what + ": both \"Le\" and \"temperature\" (pbrt-v4 refuses them together)");
        if (ps.find("Le")) m->Le = emission(ps, "Le", "MakeNamedMedium");
        if (ps.find("Lescale")) grid("Lescale", false, &m->le_scale);
        m->temperature_offset = ps.get_float("temperatureoffset", ps.get_float("temperaturecutoff", 0.0));
        m->temperature_scale = ps.get_float("temperaturescale", 1.0);
        if (!std::isfinite(m->temperature_offset) || !std::isfinite(m->temperature_scale))
            throw SceneError(m->where + ": " + what + ": the temperature's offset and scale must be finite");
    }

    // A "nanovdb" medium's grids, read with NanoVDB's reader (nanovdb_grid.h) from the file pbrt-v4's path rule
    // finds: the float grid "gridname" (default "density"; pbrt-v4 needs it) and, if the file has it, the float
    // grid "temperaturename" (default "temperature"), which makes the medium glow as pbrt-v4's does. The box
    // is the grids' world boxes together, in the medium's space (the transform in force, grid_medium).
    void nanovdb_medium(const ParamSet &ps, Medium *m)
    {
        const std::string what = "MakeNamedMedium \"" + m->name + "\"";
        const Param *file = ps.find("filename", "string");
        if (!file || ps.get_string("filename", "").empty())
            throw SceneError((file ? file->where : m->where) + ": " + what + ": no \"string filename\" (pbrt-v4 needs it)");
        const std::string path = resolve(ps.get_string("filename", ""));
        auto load = [&](const std::string &grid) -> std::shared_ptr<const NanoVdbGrid> {
            try {
                return NanoVdbGrid::load(path, grid);
            } catch (const std::runtime_error &e) {
                throw SceneError(file->where + ": " + what + ": " + path + ": " + e.what());
            }
        };
        const std::string density = ps.get_string("gridname", "density");
        m->vdb_density = load(density);
        if (!m->vdb_density)
            throw SceneError(file->where + ": " + what + ": " + path + ": no grid named \"" + density +
                             "\" (pbrt-v4 needs its density grid)");
        m->vdb_temperature = load(ps.get_string("temperaturename", "temperature"));
        m->p0 = m->vdb_density->world_min(), m->p1 = m->vdb_density->world_max();
        if (m->vdb_temperature)
            for (int k = 0; k < 3; ++k) {
                m->p0[k] = std::min(m->p0[k], m->vdb_temperature->world_min()[k]);
                m->p1[k] = std::max(m->p1[k], m->vdb_temperature->world_max()[k]);
            }
        for (int k = 0; k < 3; ++k)
            if (!(m->p1[k] > m->p0[k]) || !std::isfinite(m->p1[k] - m->p0[k]))
                throw SceneError(file->where + ": " + what + ": " + path + ": the box of its grids' active voxels is empty "
                                 "along an axis");
        double le_scale = ps.get_float("Lescale", 1.0);
        if (!std::isfinite(le_scale))
            throw SceneError(ps.find("Lescale")->where + ": " + what + ": Lescale must be finite");
        m->le_scale = {(float)le_scale};
        m->temperature_offset = ps.get_float("temperatureoffset", ps.get_float("temperaturecutoff", 0.0));
        m->temperature_scale = ps.get_float("temperaturescale", 1.0);
        if (!std::isfinite(m->temperature_offset) || !std::isfinite(m->temperature_scale))
            throw SceneError(m->where + ": " + what + ": the temperature's offset and scale must be finite");
    }

    // An absorption or scattering coefficient as linear sRGB: an rgb triple as it is (pbrt-v4's unbounded RGB
    // spectrum of it), a spectrum (pairs, a file, a named one) or a blackbody (normalized to 1 at its peak, as
    // pbrt-v4 normalizes it) as its RGB under D65 without clamping: the RGB that the round trip of an rgb
    // coefficient through pbrt-v4's spectrum gives back, as udm1-pt reduces reflectances, unclamped.
    Vec3 coefficient(const Param &p, const std::string &what)
    {
        Vec3 rgb;
        if (p.type == "rgb" && p.numbers.size() == 3) {
            rgb = Vec3(p.numbers[0], p.numbers[1], p.numbers[2]);
        } else if (p.type == "spectrum" || p.type == "blackbody") {
            Spectrum s;
            if (p.type == "blackbody") {
                if (p.numbers.size() != 1 || !(p.numbers[0] >= 1000 && p.numbers[0] <= 40000))
                    throw SceneError(p.where + ": " + what + ": \"blackbody " + p.name + "\" needs one temperature in 1000..40000 K");
                s = Spectrum::blackbody(p.numbers[0]);
            } else {
                const Spectrum *named = p.strings.size() == 1 ? named_spectrum(p.strings[0]) : nullptr;
                s = named ? *named : spectrum_from_pairs(p.numbers, p.where);
            }
            double peak = p.type == "blackbody" ? s.at(2.8977721e6 / p.numbers[0]) : 1;  // Wien's displacement law
            double v[WAVELENGTHS];
            for (int l = 0; l < WAVELENGTHS; ++l) {
                v[l] = s.at(360 + l) / peak;
                if (!(v[l] >= 0))
                    throw SceneError(p.where + ": " + what + ": '" + p.name + "' is negative at " + std::to_string(360 + l) + " nm");
            }
            rgb = albedo_rgb(v);
            rgb = Vec3(std::max(0.0, rgb.x), std::max(0.0, rgb.y), std::max(0.0, rgb.z));  // (outside the gamut)
        } else {
            throw SceneError(p.where + ": " + what + ": '" + p.name +
                             "' must be \"rgb\", \"spectrum\" or \"blackbody\" (pbrt-v4 reads no other type for it)");
        }
        if (!(rgb.x >= 0 && rgb.y >= 0 && rgb.z >= 0))
            throw SceneError(p.where + ": " + what + ": '" + p.name + "' must not be negative");
        return rgb;
    }

    void on_MediumInterface(const Call &c)
    {
        Lexer &lex = c.lex;
        const std::string &d = c.t.text;
        std::string inside = string_arg(lex, d), outside = inside;
        if (lex.peek().kind == Token::String) outside = string_arg(lex, d);
        st_.inside = inside, st_.outside = outside, st_.media_where = c.here;  // (looked up where used, as pbrt-v4)
    }

    // pbrt-v4 gives a shape whose material is "interface" (or "" or "none", its deprecated names) no area light:
    // it only bounds media. Left out here too, with a note.
    void interface_lights()
    {
        size_t n = 0;
        std::string first;
        for (Shape &s : scene_.shapes) {
            if (s.light < 0 || s.material < 0) continue;
            const std::string &type = scene_.materials[s.material].type;
            if (type != "interface" && type != "" && type != "none") continue;
            if (n++ == 0) first = s.where;
            s.light = -1;
        }
        if (n)
            scene_.notes.push_back(first + ": the AreaLightSource of a shape with the \"interface\" material is left out, as "
                                           "pbrt-v4 leaves it out (" + std::to_string(n) + (n == 1 ? " shape)" : " shapes)"));
    }

    // The media of the shapes and the camera, by name, as pbrt-v4 finds them once the file is read: a name no
    // MakeNamedMedium made is refused where something uses it; so is a grid medium that Integrator "volpath"
    // would render (under "path" media are left out: main.cpp notes it).
    void resolve_media()
    {
        const bool volpath = scene_.integrator == "volpath";
        auto find = [&](const std::string &name, const std::string &mi_where, const std::string &user,
                        bool rendered) -> int {
            if (name.empty()) return -1;
            auto it = media_.find(name);
            if (it == media_.end())
                throw SceneError(mi_where + ": MediumInterface: medium \"" + name + "\" was not made (used by " + user + ")");
            if (it->second.index < 0 && volpath && rendered)
                throw SceneError(it->second.where + ": MakeNamedMedium \"" + name + "\": type \"" + it->second.type +
                                 "\" is not modelled, and " + user +
                                 " is in it under Integrator \"volpath\" (homogeneous, uniformgrid, cloud and nanovdb media only)");
            return it->second.index;
        };
        scene_.camera.medium = find(camera_media_[0], camera_media_[1], "the Camera at " + camera_media_[2], true);
        for (size_t i = 0; i < scene_.shapes.size(); ++i) {
            const std::array<std::string, 3> &m = shape_media_[i];
            const std::string user = "the Shape at " + scene_.shapes[i].where;
            // the same medium on both sides is no transition: pbrt-v4 looks it up and then ignores it
            const bool transition = m[0] != m[1];
            int inside = find(m[0], m[2], user, transition), outside = find(m[1], m[2], user, transition);
            if (transition) scene_.shapes[i].inside = inside, scene_.shapes[i].outside = outside;
        }
    }

    // An emitting sphere under transform m: refused where pbrt-v4's image of it is not consistent. pbrt-v4
    // intersects a sphere in object space (any affine transform) but samples a sphere light as the sphere
    // of its object-space radius about its world centre, with normals flipped by ReverseOrientation
    // only: under a transform that scales or shears it, or (one-sided) swaps handedness, light sampling
    // and the rays that hit the light see different lights.
    void sphere_light_transform(const std::string &here, const Mat4 &m, bool twosided)
    {
        double scale;
        if (!m.similarity(RIGID_TOLERANCE, &scale) || std::fabs(scale - 1) > RIGID_TOLERANCE)
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
    void light_source(Lexer &lex, const Token &t)
    {
        const std::string here = where(t);
        std::string type = string_arg(lex, "LightSource");
        ParamSet ps = with_attributes(params(lex, t), LIGHT);
        const double PI = 3.14159265358979323846;
        LightSource l;
        l.where = here;
        const Mat4 &m = st_.ctm[0];  // (pbrt-v4 places a light by the start transform, with a warning if it moves)
        if (!same(st_.ctm[0], st_.ctm[1]))
            scene_.notes.push_back(here + ": LightSource \"" + type + "\" moves (ActiveTransform): placed by its start "
                                          "transform, as pbrt-v4 places it");
        // (an environment uses directions only: pbrt-v4 turns them by the upper 3x3 of the transform and of its
        // inverse, which agree - and ignore the bottom row - where the transform moves nothing)
        bool directions_only = type == "infinite" && m.m[0][3] == 0 && m.m[1][3] == 0 && m.m[2][3] == 0;
        if (!m.affine() && !directions_only) throw SceneError(here + ": LightSource \"" + type + "\": " + PROJECTIVE);
        double similar_scale;
        const bool similar = m.similarity(RIGID_TOLERANCE, &similar_scale);
        auto emitted = [&](const char *name) { return ps.find(name) ? emission(ps, name, "LightSource") : Vec3(1, 1, 1); };
        double scale = ps.get_float("scale", 1.0), power = ps.get_float("power", -1), lux = ps.get_float("illuminance", -1);
        if (!(scale >= 0) || !std::isfinite(scale)) throw SceneError(here + ": LightSource: scale must not be negative");
        if (type == "point" || type == "spot") {
            only(ps, {"I", "scale", "power", "from", "to", "coneangle", "conedeltaangle"}, "LightSource \"" + type + "\"", false,
                 &LIGHT_PARAMETERS);
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
            only(ps, {"L", "scale", "from", "to", "illuminance"}, "LightSource \"distant\"", false, &LIGHT_PARAMETERS);
            l.kind = LightSource::Distant;
            Vec3 w = m.vector(ps.get_point("from", Vec3()) - ps.get_point("to", Vec3(0, 0, 1)));
            if (!(length(w) > 0)) throw SceneError(here + ": LightSource \"distant\": from and to coincide");
            l.direction = normalize(w);
            Vec3 L = emitted("L");
            if (lux > 0) scale *= lux;
            l.L = L * scale;
        } else if (type == "infinite") {
            only(ps, {"L", "scale", "filename", "illuminance", "portal"}, "LightSource \"infinite\"", false, &LIGHT_PARAMETERS);
            if (const Param *p = ps.find("portal", "point3")) portal(*p, &l);
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
                l.filename = resolve(file);
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

    void shape(Lexer &lex, const Token &t)
    {
        const std::string here = where(t);
        std::string type = string_arg(lex, "Shape");
        ParamSet ps = with_attributes(params(lex, t), SHAPE);
        Shape s;
        s.where = here;
        s.material = st_.material;
        s.reverse_orientation = st_.reverse;
        s.object = current_object_;
        if (st_.light_template >= 0) { /* every shape of the block gets its own emitter */
            if (current_object_ >= 0)  // pbrt-v4 warns and attaches lights it never samples
                throw SceneError(here + ": an area light inside ObjectBegin (" + templates_[st_.light_template].where +
                                        ") is not modelled: pbrt-v4 does not support area lights in instances (it warns, "
                                        "and renders them inconsistently)");
            scene_.lights.push_back(templates_[st_.light_template]);
            s.light = (int)scene_.lights.size() - 1;
        }
        // a transform that swaps handedness flips the geometric normal too (pbrt)
        const Mat4 &m = still(here, "the shape");
        if (m.determinant3() < 0) s.reverse_orientation = !s.reverse_orientation;
        if (type == "trianglemesh") {
            only(ps, {"indices", "P", "N", "uv", "alpha"}, "trianglemesh", false, &SHAPE_PARAMETERS);  // ("st": pbrt-v4 reads it only when upgrading a file)
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
            only(ps, {"filename", "displacement", "edgelength", "alpha"}, "plymesh", false, &SHAPE_PARAMETERS);
            const Param *disp = ps.find("displacement");
            double edge = 1;
            if (disp && geometry_only_) {
                ignore(disp->where, "plymesh displacement (the mesh is used undisplaced)");
                disp = nullptr;
            } else if (disp) {  // displaced when the scene is complete (its texture may come later): resolve_displacements
                if (disp->type != "texture" || disp->strings.size() != 1)
                    throw SceneError(disp->where + ": plymesh: displacement must be \"texture displacement\" naming one "
                                                   "float texture");
                edge = ps.get_float("edgelength", 1.0);
                if (!(edge > 0 && edge < 1e30))
                    throw SceneError((ps.find("edgelength") ? ps.find("edgelength")->where : disp->where) +
                                     ": plymesh: edgelength must be a positive number");
                if (!m.affine()) throw SceneError(here + ": plymesh with displacement: " + PROJECTIVE);
            }
            std::string file = ps.get_string("filename", "");
            if (file.empty()) throw SceneError(here + ": plymesh needs \"string filename\"");
            try {  // the PLY's own complaint, and where the scene asked for it
                read_ply(resolve(file), disp ? Mat4() : m, &s);
            } catch (const SceneError &e) {
                throw SceneError(here + ": plymesh: " + e.what() + where_looked(file, resolve(file)));
            }
            if (disp) {
                if (s.UV.empty())
                    throw SceneError(disp->where + ": plymesh displacement needs the mesh's vertex uv (" + file +
                                     " has none; pbrt-v4 refuses it too)");
                PendingDisplacement pd;
                pd.shape = scene_.shapes.size(), pd.name = disp->strings[0], pd.where = disp->where, pd.edge = edge;
                pd.world_from_object = m, pd.reverse = st_.reverse;
                pd.mesh.P = s.P, pd.mesh.N = s.N, pd.mesh.UV = s.UV, pd.mesh.indices = s.indices;
                pending_displacements_.push_back(std::move(pd));
                to_world(m, &s);  // (undisplaced until then)
            }
        } else if (type == "sphere") {
            only(ps, {"radius", "alpha"}, "sphere", false, &SHAPE_PARAMETERS);
            double r = ps.get_float("radius", 1.0);
            if (!(r > 0)) throw SceneError(here + ": sphere radius must be positive");
            if (!m.affine()) throw SceneError(here + ": sphere: " + PROJECTIVE);
            if (!make_sphere(m, r, &s)) throw SceneError(here + ": sphere: singular transform");
            if (s.light >= 0) sphere_light_transform(here, m, templates_[st_.light_template].twosided);
        } else if (type == "disk" || type == "cylinder") {
            quadric_shape(type, ps, here, m, &s);
        } else if (type == "bilinearmesh") {
            bilinear_shape(ps, here, m, &s);
        } else if (type == "loopsubdiv") {
            loop_subdivision_shape(ps, here, m, &s);
        } else {
            throw SceneError(here + ": Shape \"" + type + "\" is not supported (trianglemesh, plymesh, sphere, disk, "
                                    "cylinder, bilinearmesh, loopsubdiv)");
        }
        shape_alpha(ps, here, &s);
        if (s.kind == Shape::Triangles && s.indices.empty()) throw SceneError(here + ": the shape has no triangles");
        if (!s.N.empty()) {  // vertex normals: pbrt-v4 transforms them by the inverse transpose (normal()) and
                             // ReverseOrientation flips them; the geometric normal then faces them
            if (!m.affine()) throw SceneError(here + ": " + type + " with normals: " + PROJECTIVE);
            if (st_.reverse)
                for (float &x : s.N) x = -x;
        }
        if (!st_.named_material.empty()) pending_materials_.push_back({scene_.shapes.size(), st_.named_material, st_.named_where});
        scene_.shapes.push_back(std::move(s));
        shape_media_.push_back({st_.inside, st_.outside, st_.media_where});
    }

    // pbrt-v4's "float alpha" (a constant; 1 and above: none) or "texture alpha" (a float texture).
    void shape_alpha(const ParamSet &ps, const std::string &here, Shape *s)
    {
        const Param *p = ps.find("alpha");
        if (!p) return;
        if (p->type == "float") {
            double a = ps.get_float("alpha", 1.0);
            if (!std::isfinite(a)) throw SceneError(p->where + ": alpha must be a finite number");
            s->alpha = std::min(a, 1.0);
        } else if (p->type == "texture") {
            if (p->strings.size() != 1) throw SceneError(p->where + ": 'alpha' needs one texture name");
            if (geometry_only_) return ignore(p->where, "Shape \"texture alpha\" (the shapes are solid)");
            // (found when the scene is complete, as pbrt-v4 finds it: resolve_textures)
            pending_alpha_.push_back({scene_.shapes.size(), p->strings[0], p->where});
            s->alpha_tex = 0;  // (a texture: has_alpha())
        } else {
            throw SceneError(p->where + ": 'alpha' must be \"float alpha\" or \"texture alpha\"");
        }
        if (s->light >= 0 && (s->alpha_tex >= 0 || s->alpha > 0) && s->has_alpha())
            throw SceneError(p->where + ": an emitting shape with an alpha texture or an alpha between 0 and 1 is not "
                                        "modelled: pbrt-v4 lets rays through it by a hash of the ray but masks its "
                                        "emission by a hash of the point, so the light that rays find and the light "
                                        "it samples differ (alpha 0, a light only light sampling finds, is modelled)");
        (void)here;
    }

    // pbrt-v4's disk (radius, innerradius, height, phimax) and cylinder (radius, zmin, zmax, phimax), met in
    // their object space (quadrics.h). An emitting one is refused where pbrt-v4's image of it is not
    // consistent: pbrt-v4 samples a disk light over its whole radius and 2 pi, and samples both by their
    // object-space area with their normals flipped by ReverseOrientation only.
    void quadric_shape(const std::string &type, const ParamSet &ps, const std::string &here, const Mat4 &m, Shape *s)
    {
        const double PI = 3.14159265358979323846;
        bool disk = type == "disk";
        if (disk) only(ps, {"radius", "innerradius", "height", "phimax", "alpha"}, "disk", false, &SHAPE_PARAMETERS);
        else only(ps, {"radius", "zmin", "zmax", "phimax", "alpha"}, "cylinder", false, &SHAPE_PARAMETERS);
        s->kind = disk ? Shape::Disk : Shape::Cylinder;
        s->object_radius = ps.get_float("radius", 1.0);
        double phimax = ps.get_float("phimax", 360.0);
        if (!(s->object_radius > 0) || !std::isfinite(s->object_radius))
            throw SceneError(here + ": " + type + ": radius must be positive");
        if (!(phimax > 0) || !std::isfinite(phimax))
            throw SceneError(here + ": " + type + ": phimax must be positive (degrees; pbrt-v4 takes it up to 360)");
        s->phi_max = std::min(phimax, 360.0) * PI / 180;  // (pbrt-v4 clamps it to 360)
        if (disk) {
            s->inner_radius = ps.get_float("innerradius", 0.0), s->height = ps.get_float("height", 0.0);
            if (!(s->inner_radius >= 0 && s->inner_radius < s->object_radius) || !std::isfinite(s->height))
                throw SceneError(here + ": disk: innerradius must be in [0, radius) and height finite");
        } else {
            double z0 = ps.get_float("zmin", -1.0), z1 = ps.get_float("zmax", 1.0);
            s->zmin = std::min(z0, z1), s->zmax = std::max(z0, z1);  // (pbrt-v4 orders them)
            if (!(s->zmax > s->zmin) || !std::isfinite(s->zmin) || !std::isfinite(s->zmax))
                throw SceneError(here + ": cylinder: zmin and zmax must differ");
        }
        if (!m.affine()) throw SceneError(here + ": " + type + ": " + PROJECTIVE);
        if (!make_quadric(m, s)) throw SceneError(here + ": " + type + ": singular transform");
        if (s->light < 0) return;
        if (disk && (s->inner_radius > 0 || phimax < 360))
            throw SceneError(here + ": an emitting disk with an innerradius or a phimax below 360 is not modelled: "
                                    "pbrt-v4 samples a disk light over its whole radius and 2 pi, so the light it "
                                    "samples and the light its rays find differ");
        double scale;
        if (!m.similarity(1e-9, &scale) || std::fabs(scale - 1) > 1e-9)
            throw SceneError(here + ": an emitting " + type + " under a transform that scales or shears it is not "
                                    "modelled: pbrt-v4 samples it by its object-space area, so its image is not "
                                    "consistent (give its size by its parameters)");
        if (m.determinant3() < 0 && !templates_[st_.light_template].twosided)
            throw SceneError(here + ": a one-sided emitting " + type + " under a transform that swaps handedness is "
                                    "not modelled: pbrt-v4 flips its normals where rays hit it but not where it "
                                    "samples it, so its image is not consistent (use ReverseOrientation, or \"bool "
                                    "twosided\" true)");
    }

    // pbrt-v4's bilinearmesh: P, indices (4 per patch: p00 p10 p01 p11; one patch of 4 vertices without
    // them), optional N and uv per vertex.
    void bilinear_shape(const ParamSet &ps, const std::string &here, const Mat4 &m, Shape *s)
    {
        only(ps, {"P", "indices", "N", "uv", "faceIndices", "alpha"}, "bilinearmesh", false, &SHAPE_PARAMETERS);
        s->kind = Shape::Bilinear;
        const Param *P = ps.find("P", "point3"), *I = ps.find("indices", "integer");
        if (!P || P->numbers.size() % 3 || P->numbers.empty())
            throw SceneError(here + ": bilinearmesh needs \"point3 P\" with 3 numbers per vertex");
        size_t nv = P->numbers.size() / 3;
        std::vector<double> idx;
        if (I) idx = I->numbers;
        else if (nv == 4) idx = {0, 1, 2, 3};
        else throw SceneError(here + ": bilinearmesh needs \"integer indices\"");
        if (idx.empty() || idx.size() % 4)
            throw SceneError((I ? I->where : here) + ": bilinearmesh: the indices are not a multiple of 4");
        for (double v : idx)
            if (!(v >= 0 && v < (double)nv) || v != std::floor(v))
                throw SceneError((I ? I->where : here) + ": bilinearmesh: index " + number_text(v) + " out of range (" +
                                 std::to_string(nv) + " vertices)");
        if (const Param *F = ps.find("faceIndices", "integer"))
            if (F->numbers.size() != idx.size() / 4)
                throw SceneError(F->where + ": bilinearmesh: faceIndices needs one index per patch");
        for (size_t k = 0; k < nv; ++k) {
            Vec3 p = m.point(Vec3(P->numbers[3 * k], P->numbers[3 * k + 1], P->numbers[3 * k + 2]));
            s->P.insert(s->P.end(), {(float)p.x, (float)p.y, (float)p.z});
        }
        for (double v : idx) s->indices.push_back((uint32_t)v);
        if (const Param *N = ps.find("N", "normal")) {
            if (N->numbers.size() != 3 * nv) throw SceneError(N->where + ": bilinearmesh: N needs one normal per vertex");
            for (size_t k = 0; k < nv; ++k) {
                Vec3 n = normalize(m.normal(Vec3(N->numbers[3 * k], N->numbers[3 * k + 1], N->numbers[3 * k + 2])));
                s->N.insert(s->N.end(), {(float)n.x, (float)n.y, (float)n.z});
            }
        }
        if (const Param *uv = ps.find("uv", "point2")) {
            if (uv->numbers.size() != 2 * nv) throw SceneError(uv->where + ": bilinearmesh: uv needs 2 numbers per vertex");
            for (double v : uv->numbers) s->UV.push_back((float)v);
        }
    }

    // pbrt-v4's loopsubdiv: the mesh refined "levels" times by Loop's rules at load time, its vertices on
    // the limit surface with the limit normals (loop_subdivision.h), in object space, then placed.
    void loop_subdivision_shape(const ParamSet &ps, const std::string &here, const Mat4 &m, Shape *s)
    {
        only(ps, {"P", "indices", "levels", "scheme", "alpha"}, "loopsubdiv", false, &SHAPE_PARAMETERS);
        const Param *P = ps.find("P", "point3"), *I = ps.find("indices", "integer");
        if (!P || P->numbers.size() % 3 || P->numbers.empty())
            throw SceneError(here + ": loopsubdiv needs \"point3 P\" with 3 numbers per vertex");
        if (!I || I->numbers.empty() || I->numbers.size() % 3)
            throw SceneError(here + ": loopsubdiv needs \"integer indices\", 3 per triangle");
        std::string scheme = ps.get_string("scheme", "loop");
        if (scheme != "loop") throw SceneError(ps.find("scheme")->where + ": loopsubdiv: scheme \"" + scheme + "\" is not \"loop\"");
        int levels = ps.get_int("levels", 3);
        size_t nv = P->numbers.size() / 3, nf = I->numbers.size() / 3;
        if (levels < 0 || levels > 12 || (double)nf * std::pow(4.0, levels) > 1e8)
            throw SceneError(here + ": loopsubdiv: levels " + std::to_string(levels) + " is outside 0..12 or makes more "
                                    "than 1e8 triangles");
        std::vector<uint32_t> idx;
        for (double v : I->numbers) {
            if (!(v >= 0 && v < (double)nv) || v != std::floor(v))
                throw SceneError(I->where + ": loopsubdiv: index " + number_text(v) + " out of range (" + std::to_string(nv) +
                                 " vertices)");
            idx.push_back((uint32_t)v);
        }
        std::vector<Vec3> pts;
        for (size_t k = 0; k < nv; ++k) pts.emplace_back(P->numbers[3 * k], P->numbers[3 * k + 1], P->numbers[3 * k + 2]);
        LoopMesh mesh;
        std::string why;
        if (!loop_subdivide(idx, pts, levels, &mesh, &why))
            throw SceneError(here + ": loopsubdiv: the mesh cannot be subdivided by Loop's rules: " + why);
        if (!m.affine()) throw SceneError(here + ": loopsubdiv: " + PROJECTIVE);
        Mat4 inv;
        if (!m.inverse(&inv)) throw SceneError(here + ": loopsubdiv: singular transform");
        for (Vec3 p : mesh.P) {
            p = m.point(p);
            s->P.insert(s->P.end(), {(float)p.x, (float)p.y, (float)p.z});
        }
        for (Vec3 n : mesh.N) {  // by the inverse transpose, not normalized: pbrt-v4 interpolates them as they are
            Vec3 w(inv.m[0][0] * n.x + inv.m[1][0] * n.y + inv.m[2][0] * n.z, inv.m[0][1] * n.x + inv.m[1][1] * n.y + inv.m[2][1] * n.z,
                   inv.m[0][2] * n.x + inv.m[1][2] * n.y + inv.m[2][2] * n.z);
            s->N.insert(s->N.end(), {(float)w.x, (float)w.y, (float)w.z});
        }
        s->indices = std::move(mesh.indices);
    }

    // An infinite light's "portal": four points of a rectangle. pbrt-v4's PortalImageInfiniteLight samples the
    // environment through it, and lets it light the scene only along rays through it; udm1-pt renders the
    // environment as without a portal (every direction): the same image where the scene sees the environment
    // only through the portal (a window), the case portals are made for.
    void portal(const Param &p, LightSource *)
    {
        if (p.numbers.size() != 12)
            throw SceneError(p.where + ": LightSource \"infinite\": portal needs 4 points (12 numbers), pbrt-v4's rectangle");
        scene_.notes.push_back(p.where + ": LightSource \"infinite\": portal ignored: pbrt-v4 samples the environment "
                                         "through it and lets it light the scene only through it, udm1-pt from every "
                                         "direction (the same image where the scene sees the environment only through "
                                         "the portal)");
    }

    // A texture's texture-valued parameters, as pbrt-v4 finds them when it creates the textures: image
    // textures first (each file's first), then the float textures in the order they were made, then the
    // spectrum textures; so a texture may use one of its kind made before it, a float texture made anywhere
    // (from a spectrum texture), or an image texture made anywhere. A shape's alpha texture: any float texture.
    void resolve_textures()
    {
        for (const PendingTexture &pt : pending_textures_) {
            Texture &tx = scene_.textures[pt.texture];
            auto it = textures_.find({pt.kind, pt.name});
            if (it == textures_.end())
                throw SceneError(pt.where + ": texture \"" + quote(pt.name) + "\" was not made (a " + pt.kind + " texture)");
            if ((size_t)it->second > pt.texture && !image_first_[it->second] && pt.kind == tx.kind)
                throw SceneError(pt.where + ": texture \"" + quote(pt.name) + "\" is made after the texture that uses it (at " +
                                 scene_.textures[it->second].where + "): pbrt-v4 makes textures in order, image textures "
                                 "first, and refuses it");
            (tx.*pt.input).tex = it->second;
        }
        for (const PendingAlpha &pa : pending_alpha_) {
            auto it = textures_.find({"float", pa.name});
            if (it == textures_.end())
                throw SceneError(pa.where + ": alpha: float texture \"" + quote(pa.name) + "\" was not made");
            scene_.shapes[pa.shape].alpha_tex = it->second;
        }
    }

    // Each ObjectInstance: the object of its name, made anywhere in the scene (pbrt-v4 resolves the names
    // when it builds the scene); an object without shapes places nothing, as in pbrt-v4.
    void resolve_instances()
    {
        std::vector<bool> used(scene_.objects.size(), false);
        for (const Shape &s : scene_.shapes)
            if (s.object >= 0) used[s.object] = true;
        for (const PendingInstance &pi : pending_instances_) {
            auto it = object_index_.find(pi.name);
            if (it == object_index_.end()) throw SceneError(pi.where + ": ObjectInstance \"" + quote(pi.name) + "\": no such object");
            if (!used[it->second]) continue;
            Instance in;
            in.object = it->second, in.world_from_object = pi.world_from_object, in.where = pi.where;
            if (!in.world_from_object.affine()) throw SceneError(pi.where + ": ObjectInstance: " + PROJECTIVE);
            if (!in.world_from_object.inverse(&in.object_from_world))
                throw SceneError(pi.where + ": ObjectInstance: singular transform");
            scene_.instances.push_back(in);
        }
    }

    static const std::set<std::string> SHAPE_PARAMETERS, LIGHT_PARAMETERS, TEXTURE_PARAMETERS;

    struct NamedMaterial {
        int index;
        std::string where;
    };
    struct PendingMaterial {  // a shape's NamedMaterial
        size_t shape;
        std::string name, where;
    };
    struct PendingTexture {  // a texture's texture-valued parameter
        size_t texture;
        TextureInput Texture::*input;
        std::string kind, name, where;
    };
    struct PendingDisplacement {  // a plymesh's "texture displacement": its object-space mesh
        size_t shape;
        std::string name, where;
        double edge;
        Mat4 world_from_object;
        bool reverse;
        DisplacedMesh mesh;
    };
    std::vector<PendingDisplacement> pending_displacements_;

    // An object-space triangle mesh into world space: points by m, normals by its inverse transpose, normalized.
    static void to_world(const Mat4 &m, Shape *s)
    {
        for (size_t k = 0; k + 2 < s->P.size(); k += 3) {
            Vec3 p = m.point(Vec3(s->P[k], s->P[k + 1], s->P[k + 2]));
            s->P[k] = (float)p.x, s->P[k + 1] = (float)p.y, s->P[k + 2] = (float)p.z;
        }
        for (size_t k = 0; k + 2 < s->N.size(); k += 3) {
            Vec3 n = normalize(m.normal(Vec3(s->N[k], s->N[k + 1], s->N[k + 2])));
            s->N[k] = (float)n.x, s->N[k + 1] = (float)n.y, s->N[k + 2] = (float)n.z;
        }
    }

    // Each displaced plymesh refined and displaced by its float texture (displacement.h), made anywhere in the scene.
    void resolve_displacements()
    {
        for (PendingDisplacement &pd : pending_displacements_) {
            auto it = textures_.find({"float", pd.name});
            if (it == textures_.end())
                throw SceneError(pd.where + ": displacement: float texture \"" + quote(pd.name) + "\" was not made");
            Textures tex(scene_, {it->second});
            int t = it->second;
            displace_mesh(pd.mesh, pd.world_from_object, pd.edge, [&](const Vec3 &p, double u, double v) {
                TexturePoint at;
                at.p = p, at.u = u, at.v = v;
                return tex.value(t, at);
            });
            Shape &s = scene_.shapes[pd.shape];
            s.P = std::move(pd.mesh.P), s.N = std::move(pd.mesh.N), s.UV = std::move(pd.mesh.UV);
            s.indices = std::move(pd.mesh.indices);
            to_world(pd.world_from_object, &s);
            if (pd.reverse)
                for (float &x : s.N) x = -x;
        }
        pending_displacements_.clear();
    }

    struct PendingAlpha {  // a shape's "texture alpha"
        size_t shape;
        std::string name, where;
    };
    struct PendingInstance {
        std::string name;
        Mat4 world_from_object;
        std::string where;
    };

    Scene &scene_;
    State st_;
    std::vector<State> stack_;                             // AttributeBegin and ObjectBegin push the state
    std::vector<std::pair<char, std::string>> blocks_;     // ... 'a' or 'o', and where
    std::map<std::string, NamedMaterial> named_;
    std::map<std::string, std::shared_ptr<const TabulatedBsdf>> tabulated_;  // the measured materials' files, by path
    std::vector<PendingMaterial> pending_materials_;
    std::vector<AreaLight> templates_;  // AreaLightSource of the blocks; each shape gets a copy
    bool camera_set_ = false, in_world_ = false;
    bool geometry_only_ = false;
    std::set<std::string> ignored_kinds_;
    struct NamedMedium {
        int index;  // Scene::media, or -1 for a medium not modelled (rgbgrid)
        std::string type, where;
    };
    std::map<std::string, NamedMedium> media_;           // MakeNamedMedium's, by name
    std::vector<std::array<std::string, 3>> shape_media_;  // each shape's inside and outside media, MediumInterface's file:line
    std::array<std::string, 3> camera_media_;            // the camera's medium, MediumInterface's and Camera's file:line
    std::map<std::pair<std::string, std::string>, int> textures_;  // (kind, name): float and spectrum textures
                                                                   // have names of their own, as in pbrt-v4
    std::vector<bool> image_first_;   // per texture: an image texture, the first of its file
    std::set<std::string> image_files_;
    bool noise_texture_noted_ = false;  // the noise textures' note is made once, at the first
    std::vector<PendingTexture> pending_textures_;
    std::vector<PendingAlpha> pending_alpha_;
    std::map<std::string, std::array<Mat4, 2>> coordinate_systems_;
    double transform_times_[2] = {0, 1};
    std::map<std::string, int> object_index_;
    int current_object_ = -1;
    std::vector<PendingInstance> pending_instances_;
    size_t import_floor_ = 0, object_floor_ = 0;  // the block depth at the Import being read; an object open outside it
    int import_depth_ = 0;
    double iso_ = 100;
    std::string film_where_, shutter_where_;
    std::deque<std::string> names_;  // the files read (tokens point at them)
};

const std::set<std::string> Parser::SHAPE_PARAMETERS = {"indices", "P",          "N",      "uv",     "filename",
                                                         "displacement", "edgelength", "radius", "alpha", "innerradius",
                                                         "height",  "phimax",     "zmin",   "zmax",   "faceIndices",
                                                         "levels",  "scheme"};
const std::set<std::string> Parser::LIGHT_PARAMETERS = {"I",     "scale", "power",       "from",     "to",
                                                         "coneangle", "conedeltaangle", "L", "illuminance",
                                                         "filename",  "portal",         "twosided"};
const std::set<std::string> Parser::TEXTURE_PARAMETERS = {
    "filename", "encoding", "invert", "scale",  "wrap",   "filter", "maxanisotropy", "tex", "value", "tex1", "tex2", "amount",
    "dir",      "dimension", "mapping", "uscale", "vscale", "udelta", "vdelta",       "v1",  "v2"};

}  // namespace

Scene parse_pbrt(const std::string &path, Need need)
{
    Scene scene;
    scene.source = path;
    Parser p(scene, need);
    p.parse_main(path);
    p.finish();
    // pbrt-v4 renders a scene without shapes (its lights seen directly, its media); an occlusion job has nothing to do
    if (need == Need::Geometry &&
        std::none_of(scene.shapes.begin(), scene.shapes.end(), [](const Shape &s) { return s.object < 0; }) &&
        scene.instances.empty())
        throw SceneError(path + ": the scene has no shapes");
    return scene;
}

}  // namespace udm1scene
