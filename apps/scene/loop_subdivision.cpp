// loop_subdivision.cpp - see loop_subdivision.h. The mesh is kept as faces with their neighbours across
// each edge (as pbrt-v4 keeps it: neighbour k lies across the edge from vertex k to vertex k + 1), rebuilt
// from the faces after every level; each vertex's ring is walked through the neighbours in pbrt-v4's
// order, so that the limit normals point the way pbrt-v4's do.
#include "loop_subdivision.h"

#include <array>
#include <cmath>
#include <unordered_map>
#include <unordered_set>

namespace udm1scene {

namespace {

const double PI = 3.14159265358979323846;
inline int next(int i) { return (i + 1) % 3; }
inline int prev(int i) { return (i + 2) % 3; }
inline uint64_t edge_key(int a, int b) { return a < b ? ((uint64_t)a << 32) | (uint32_t)b : ((uint64_t)b << 32) | (uint32_t)a; }

struct Topology {
    std::vector<std::array<int, 3>> fv, ff;  // each face's vertices; its neighbour across edge k, or -1
    std::vector<int> start, valence;         // a face of each vertex; its valence (boundary: faces + 1)
    std::vector<char> boundary;

    int vnum(int f, int v) const { return fv[f][0] == v ? 0 : fv[f][1] == v ? 1 : 2; }
    int next_face(int f, int v) const { return ff[f][vnum(f, v)]; }
    int prev_face(int f, int v) const { return ff[f][prev(vnum(f, v))]; }
    int next_vert(int f, int v) const { return fv[f][next(vnum(f, v))]; }
    int prev_vert(int f, int v) const { return fv[f][prev(vnum(f, v))]; }
    int other_vert(int f, int a, int b) const
    {
        for (int k = 0; k < 3; ++k)
            if (fv[f][k] != a && fv[f][k] != b) return fv[f][k];
        return -1;
    }

    // The neighbours, the faces around each vertex (one fan each) and the valences, from fv.
    bool build(int nv, std::string *why)
    {
        const size_t nf = fv.size();
        ff.assign(nf, {-1, -1, -1});
        start.assign(nv, -1), valence.assign(nv, 0), boundary.assign(nv, 0);
        std::vector<int> incident(nv, 0);
        for (size_t f = 0; f < nf; ++f) {
            if (fv[f][0] == fv[f][1] || fv[f][1] == fv[f][2] || fv[f][0] == fv[f][2])
                return *why = "face " + std::to_string(f) + " repeats a vertex", false;
            for (int k = 0; k < 3; ++k) start[fv[f][k]] = (int)f, ++incident[fv[f][k]];
        }
        std::unordered_map<uint64_t, std::pair<int, int>> open;  // an edge seen once: (face, edge number)
        std::unordered_set<uint64_t> closed;                      // an edge seen twice
        open.reserve(nf * 2);
        for (size_t f = 0; f < nf; ++f)
            for (int k = 0; k < 3; ++k) {
                int a = fv[f][k], b = fv[f][next(k)];
                uint64_t key = edge_key(a, b);
                if (closed.count(key))
                    return *why = "the edge " + std::to_string(a) + "-" + std::to_string(b) + " is shared by more than two faces", false;
                auto it = open.find(key);
                if (it == open.end()) {
                    open.emplace(key, std::make_pair((int)f, k));
                    continue;
                }
                auto [f0, k0] = it->second;
                if (fv[f0][k0] == a)
                    return *why = "faces " + std::to_string(f0) + " and " + std::to_string(f) +
                                  " traverse their shared edge the same way (inconsistent orientation)", false;
                ff[f0][k0] = (int)f, ff[f][k] = f0;
                open.erase(it);
                closed.insert(key);
            }
        for (int v = 0; v < nv; ++v) {
            if (start[v] < 0) continue;
            int f = start[v], count = 1;
            while ((f = next_face(f, v)) >= 0 && f != start[v])
                if (++count > incident[v]) break;
            boundary[v] = f < 0;
            if (boundary[v]) {
                f = start[v];
                while ((f = prev_face(f, v)) >= 0)
                    if (++count > incident[v]) break;
            }
            if (count != incident[v])
                return *why = "the faces of vertex " + std::to_string(v) + " do not form one fan", false;
            valence[v] = boundary[v] ? count + 1 : count;
        }
        return true;
    }

    // pbrt-v4's one ring of v: interior, the next vertex of each face going round by next_face; boundary,
    // from the last face that way, its next vertex, then the previous vertex of each face going back.
    void ring(const std::vector<Vec3> &P, int v, std::vector<Vec3> *out) const
    {
        out->clear();
        int f = start[v];
        if (!boundary[v]) {
            do {
                out->push_back(P[next_vert(f, v)]);
                f = next_face(f, v);
            } while (f != start[v]);
            return;
        }
        for (int g; (g = next_face(f, v)) >= 0;) f = g;
        out->push_back(P[next_vert(f, v)]);
        do {
            out->push_back(P[prev_vert(f, v)]);
            f = prev_face(f, v);
        } while (f >= 0);
    }
};

double beta(int valence) { return valence == 3 ? 3.0 / 16 : 3.0 / (8.0 * valence); }
double loop_gamma(int valence) { return 1 / (valence + 3 / (8 * beta(valence))); }

Vec3 one_ring_rule(const std::vector<Vec3> &ring, Vec3 p, double b)
{
    Vec3 q = p * (1 - (double)ring.size() * b);
    for (Vec3 r : ring) q = q + r * b;
    return q;
}

Vec3 boundary_rule(const std::vector<Vec3> &ring, Vec3 p, double b)
{
    return p * (1 - 2 * b) + ring.front() * b + ring.back() * b;
}

}  // namespace

bool loop_subdivide(const std::vector<uint32_t> &indices, const std::vector<Vec3> &P, int levels, LoopMesh *out,
                    std::string *why)
{
    // the vertices that faces use, in their order (all of them used: their own numbers)
    std::vector<int> remap(P.size(), -1);
    for (uint32_t v : indices) remap[v] = 0;
    std::vector<Vec3> p;
    for (size_t v = 0; v < P.size(); ++v)
        if (remap[v] == 0) remap[v] = (int)p.size(), p.push_back(P[v]);
    Topology t;
    for (size_t i = 0; i + 2 < indices.size(); i += 3)
        t.fv.push_back({remap[indices[i]], remap[indices[i + 1]], remap[indices[i + 2]]});
    if (!t.build((int)p.size(), why)) return false;
    std::vector<Vec3> ring;
    for (int level = 0; level < levels; ++level) {
        const int nv = (int)p.size();
        std::vector<Vec3> np(nv);
        for (int v = 0; v < nv; ++v) {  // the even vertices keep their numbers
            t.ring(p, v, &ring);
            np[v] = t.boundary[v] ? boundary_rule(ring, p[v], 1.0 / 8) : one_ring_rule(ring, p[v], beta(t.valence[v]));
        }
        std::unordered_map<uint64_t, int> edge_vertex;
        edge_vertex.reserve(t.fv.size() * 2);
        std::vector<std::array<int, 3>> nf;
        nf.reserve(4 * t.fv.size());
        for (size_t f = 0; f < t.fv.size(); ++f) {
            int e[3];
            for (int k = 0; k < 3; ++k) {
                int a = t.fv[f][k], b = t.fv[f][next(k)];
                auto [it, fresh] = edge_vertex.emplace(edge_key(a, b), (int)np.size());
                e[k] = it->second;
                if (!fresh) continue;
                int g = t.ff[f][k];
                if (g < 0) np.push_back((p[a] + p[b]) * 0.5);
                else np.push_back((p[a] + p[b]) * (3.0 / 8) + (p[t.other_vert((int)f, a, b)] + p[t.other_vert(g, a, b)]) * (1.0 / 8));
            }
            const std::array<int, 3> &v = t.fv[f];
            for (int j = 0; j < 3; ++j) {  // the corner faces, then the middle one (pbrt-v4's children)
                std::array<int, 3> c;
                c[j] = v[j], c[next(j)] = e[j], c[prev(j)] = e[prev(j)];
                nf.push_back(c);
            }
            nf.push_back({e[0], e[1], e[2]});
        }
        p.swap(np);
        t.fv.swap(nf);
        if (!t.build((int)p.size(), why)) return false;  // (cannot fail once the control mesh passed)
    }
    // the limit positions, then the limit normals from the rings of limit positions
    const int nv = (int)p.size();
    out->P.assign(nv, Vec3());
    for (int v = 0; v < nv; ++v) {
        t.ring(p, v, &ring);
        out->P[v] = t.boundary[v] ? boundary_rule(ring, p[v], 1.0 / 5) : one_ring_rule(ring, p[v], loop_gamma(t.valence[v]));
    }
    out->N.assign(nv, Vec3());
    for (int v = 0; v < nv; ++v) {
        t.ring(out->P, v, &ring);
        const int n = (int)ring.size();
        Vec3 S, T, pv = out->P[v];
        if (!t.boundary[v]) {
            for (int j = 0; j < n; ++j) {
                S = S + ring[j] * std::cos(2 * PI * j / n);
                T = T + ring[j] * std::sin(2 * PI * j / n);
            }
        } else {
            S = ring[n - 1] - ring[0];
            if (n == 2) T = ring[0] + ring[1] - pv * 2;
            else if (n == 3) T = ring[1] - pv;
            else if (n == 4) T = ring[0] * -1 + ring[1] * 2 + ring[2] * 2 - ring[3] - pv * 2;
            else {
                double theta = PI / (n - 1);
                T = (ring[0] + ring[n - 1]) * std::sin(theta);
                for (int k = 1; k < n - 1; ++k) T = T + ring[k] * ((2 * std::cos(theta) - 2) * std::sin(k * theta));
                T = -T;
            }
        }
        out->N[v] = cross(S, T);
    }
    out->indices.clear();
    out->indices.reserve(3 * t.fv.size());
    for (const auto &f : t.fv)
        for (int k = 0; k < 3; ++k) out->indices.push_back((uint32_t)f[k]);
    return true;
}

}  // namespace udm1scene
