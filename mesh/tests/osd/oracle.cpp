// OpenSubdiv 3.5 as an oracle for capdiv-mesh's tests: the Catmull-Clark
// limit surface of a tagged mesh (creases, corners, holes, boundary rule,
// creasing method, triangle rule) at given ptex points, the limit positions of given
// input vertices, and — when the job has UVs — the face-varying UV channel
// interpolated with FVAR_LINEAR_ALL at the same ptex points. The job comes on stdin, the answers go to stdout (format in
// mesh/tests/osd/mod.rs); anything OpenSubdiv reports goes to stderr, and any
// error exits non-zero.
//
// Build: g++ -O2 -std=c++14 oracle.cpp -o osd-oracle -losdCPU

#include <opensubdiv/far/patchMap.h>
#include <opensubdiv/far/patchTable.h>
#include <opensubdiv/far/patchTableFactory.h>
#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/far/ptexIndices.h>
#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/far/topologyRefinerFactory.h>
#include <opensubdiv/vtr/refinement.h>

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

using namespace OpenSubdiv;

namespace {

bool g_error = false;

void onError(Far::ErrorType, const char *message) {
    std::fprintf(stderr, "OpenSubdiv error: %s\n", message);
    g_error = true;
}

void onWarning(const char *message) {
    std::fprintf(stderr, "OpenSubdiv warning: %s\n", message);
}

[[noreturn]] void fail(const char *format, ...) {
    std::fprintf(stderr, "osd-oracle: ");
    va_list args;
    va_start(args, format);
    std::vfprintf(stderr, format, args);
    va_end(args);
    std::fprintf(stderr, "\n");
    std::exit(2);
}

void checkErrors(const char *when) {
    if (g_error) fail("OpenSubdiv reported an error %s", when);
}

// A position in double, with the interface PrimvarRefinerReal<double> and
// StencilTableReal<double> expect.
struct Point {
    double p[3];
    void Clear() { p[0] = p[1] = p[2] = 0.0; }
    void AddWithWeight(Point const &src, double w) {
        p[0] += w * src.p[0];
        p[1] += w * src.p[1];
        p[2] += w * src.p[2];
    }
};

// A face-varying value (u, v) in double.
struct Uv {
    double p[2];
    void Clear() { p[0] = p[1] = 0.0; }
    void AddWithWeight(Uv const &src, double w) {
        p[0] += w * src.p[0];
        p[1] += w * src.p[1];
    }
};

// Reads the keyword `key` and its count.
int header(const char *key) {
    std::string word;
    long n = -1;
    if (!(std::cin >> word) || word != key) fail("expected '%s', got '%s'", key, word.c_str());
    if (!(std::cin >> n) || n < 0) fail("bad count after '%s'", key);
    return (int)n;
}

std::string keyword(const char *key) {
    std::string word, value;
    if (!(std::cin >> word) || word != key) fail("expected '%s', got '%s'", key, word.c_str());
    if (!(std::cin >> value)) fail("missing value after '%s'", key);
    return value;
}

template <class T> T read(const char *what) {
    T x;
    if (!(std::cin >> x)) fail("cannot read %s", what);
    return x;
}

void printPoint(Point const &q) {
    std::printf("%.17g %.17g %.17g", q.p[0], q.p[1], q.p[2]);
}

}  // namespace

int main() {
    Far::SetErrorCallback(onError);
    Far::SetWarningCallback(onWarning);

    // ---- the job
    int nv = header("vertices");
    std::vector<Point> base(nv);
    for (auto &q : base)
        for (double &c : q.p) c = read<double>("vertex coordinate");

    int nf = header("faces");
    std::vector<int> vertsPerFace(nf);
    std::vector<Far::Index> faceVerts;
    for (int f = 0; f < nf; ++f) {
        int k = read<int>("face size");
        if (k < 3) fail("face %d has %d vertices", f, k);
        vertsPerFace[f] = k;
        for (int i = 0; i < k; ++i) {
            int v = read<int>("face vertex");
            if (v < 0 || v >= nv) fail("face %d: vertex %d out of range", f, v);
            faceVerts.push_back(v);
        }
    }

    int nc = header("creases");
    std::vector<Far::Index> creaseVerts;
    std::vector<float> creaseWeights;
    std::vector<float> vertexMaxSharp(nv, 0.0f);  // finite sharpness at each vertex
    for (int i = 0; i < nc; ++i) {
        int a = read<int>("crease vertex"), b = read<int>("crease vertex");
        float s = read<float>("crease sharpness");
        if (a < 0 || a >= nv || b < 0 || b >= nv) fail("crease %d out of range", i);
        creaseVerts.push_back(a);
        creaseVerts.push_back(b);
        creaseWeights.push_back(s);
        if (s < Sdc::Crease::SHARPNESS_INFINITE) {
            vertexMaxSharp[a] = std::max(vertexMaxSharp[a], s);
            vertexMaxSharp[b] = std::max(vertexMaxSharp[b], s);
        }
    }

    int nk = header("corners");
    std::vector<Far::Index> cornerVerts;
    std::vector<float> cornerWeights;
    for (int i = 0; i < nk; ++i) {
        int v = read<int>("corner vertex");
        float s = read<float>("corner sharpness");
        if (v < 0 || v >= nv) fail("corner %d out of range", i);
        cornerVerts.push_back(v);
        cornerWeights.push_back(s);
        if (s < Sdc::Crease::SHARPNESS_INFINITE) vertexMaxSharp[v] = std::max(vertexMaxSharp[v], s);
    }

    int nh = header("holes");
    std::vector<Far::Index> holes;
    for (int i = 0; i < nh; ++i) {
        int f = read<int>("hole face");
        if (f < 0 || f >= nf) fail("hole %d out of range", f);
        holes.push_back(f);
    }

    Sdc::Options sdcOptions;
    std::string boundary = keyword("boundary");
    if (boundary == "none")
        sdcOptions.SetVtxBoundaryInterpolation(Sdc::Options::VTX_BOUNDARY_NONE);
    else if (boundary == "edge-only")
        sdcOptions.SetVtxBoundaryInterpolation(Sdc::Options::VTX_BOUNDARY_EDGE_ONLY);
    else if (boundary == "edge-and-corner")
        sdcOptions.SetVtxBoundaryInterpolation(Sdc::Options::VTX_BOUNDARY_EDGE_AND_CORNER);
    else
        fail("unknown boundary rule '%s'", boundary.c_str());
    std::string creasing = keyword("creasing");
    if (creasing == "uniform")
        sdcOptions.SetCreasingMethod(Sdc::Options::CREASE_UNIFORM);
    else if (creasing == "chaikin")
        sdcOptions.SetCreasingMethod(Sdc::Options::CREASE_CHAIKIN);
    else
        fail("unknown creasing method '%s'", creasing.c_str());
    std::string triangles = keyword("triangles");
    if (triangles == "catmark")
        sdcOptions.SetTriangleSubdivision(Sdc::Options::TRI_SUB_CATMARK);
    else if (triangles == "smooth")
        sdcOptions.SetTriangleSubdivision(Sdc::Options::TRI_SUB_SMOOTH);
    else
        fail("unknown triangle rule '%s'", triangles.c_str());

    std::string isolationText = keyword("isolation");
    int isolation = std::atoi(isolationText.c_str());
    if (isolation < 1 || isolation > 10) fail("isolation level %d not in 1..10", isolation);

    struct Query {
        int face, corner;
        double u, v;
    };
    int nq = header("queries");
    std::vector<Query> queries(nq);
    for (auto &q : queries) {
        q.face = read<int>("query face");
        q.corner = read<int>("query corner");
        q.u = read<double>("query u");
        q.v = read<double>("query v");
        if (q.face < 0 || q.face >= nf) fail("query face %d out of range", q.face);
        int k = vertsPerFace[q.face];
        if (k == 4 ? q.corner != -1 : (q.corner < 0 || q.corner >= k))
            fail("query corner %d invalid for face %d with %d vertices", q.corner, q.face, k);
    }

    int nl = header("limits");
    std::vector<int> limits(nl);
    for (int &v : limits) {
        v = read<int>("limit vertex");
        if (v < 0 || v >= nv) fail("limit vertex %d out of range", v);
    }

    // Face-varying UVs: a pool of values and one index per face corner.
    int nuv = header("uvs");
    std::vector<Uv> uvs(nuv);
    for (auto &t : uvs)
        for (double &c : t.p) c = read<double>("uv coordinate");
    std::vector<Far::Index> uvIndices;
    if (nuv > 0) {
        uvIndices.resize(faceVerts.size());
        for (auto &i : uvIndices) {
            i = read<int>("uv index");
            if (i < 0 || i >= nuv) fail("uv index %d out of range", i);
        }
    }

    // ---- topology
    Far::TopologyDescriptor desc;
    desc.numVertices = nv;
    desc.numFaces = nf;
    desc.numVertsPerFace = vertsPerFace.data();
    desc.vertIndicesPerFace = faceVerts.data();
    desc.numCreases = nc;
    desc.creaseVertexIndexPairs = creaseVerts.data();
    desc.creaseWeights = creaseWeights.data();
    desc.numCorners = nk;
    desc.cornerVertexIndices = cornerVerts.data();
    desc.cornerWeights = cornerWeights.data();
    desc.numHoles = nh;
    desc.holeIndices = holes.data();

    typedef Far::TopologyRefinerFactory<Far::TopologyDescriptor> Factory;
    Factory::Options factoryOptions(Sdc::SCHEME_CATMARK, sdcOptions);
    factoryOptions.validateFullTopology = true;

    // ---- patches: adaptive refinement, double-precision patch table
    if (nq > 0) {
        std::unique_ptr<Far::TopologyRefiner> refiner(Factory::Create(desc, factoryOptions));
        if (!refiner) fail("TopologyRefinerFactory rejected the mesh");
        checkErrors("creating the refiner");

        Far::PatchTableFactory::Options patchOptions(isolation);
        patchOptions.SetPatchPrecision<double>();
        patchOptions.useInfSharpPatch = true;
        patchOptions.useSingleCreasePatch = false;
        patchOptions.generateLegacySharpCornerPatches = false;
        patchOptions.SetEndCapType(Far::PatchTableFactory::Options::ENDCAP_GREGORY_BASIS);
        patchOptions.generateFVarTables = false;
        patchOptions.generateVaryingTables = false;

        Far::TopologyRefiner::AdaptiveOptions adaptive = patchOptions.GetRefineAdaptiveOptions();
        adaptive.useInfSharpPatch = true;
        adaptive.useSingleCreasePatch = false;
        adaptive.considerFVarChannels = false;
        refiner->RefineAdaptive(adaptive);
        checkErrors("refining adaptively");

        std::unique_ptr<Far::PatchTable> table(Far::PatchTableFactory::Create(*refiner, patchOptions));
        if (!table) fail("PatchTableFactory failed");
        checkErrors("creating the patch table");

        // Patch CVs index the vertices of all refined levels, level 0 first,
        // followed by the patch table's local (end-cap) points.
        int nRefined = refiner->GetNumVerticesTotal();
        int nLocal = table->GetNumLocalPoints();
        std::vector<Point> verts(nRefined + nLocal);
        for (int i = 0; i < nv; ++i) verts[i] = base[i];
        Far::PrimvarRefinerReal<double> primvar(*refiner);
        Point *src = verts.data();
        for (int level = 1; level < refiner->GetNumLevels(); ++level) {
            Point *dst = src + refiner->GetLevel(level - 1).GetNumVertices();
            primvar.Interpolate(level, src, dst);
            src = dst;
        }
        checkErrors("interpolating refined vertices");
        // Local points through the double stencil table (the generic
        // ComputeLocalPointValues reads the stencils as float).
        if (nLocal > 0) {
            Far::StencilTableReal<double> const *stencils = table->GetLocalPointStencilTable<double>();
            if (!stencils) fail("no double local point stencil table");
            stencils->UpdateValues(verts.data(), verts.data() + nRefined);
        }

        Far::PtexIndices ptex(*refiner);
        Far::PatchMap patchMap(*table);
        std::vector<double> w(20);
        for (auto const &q : queries) {
            int ptexFace = ptex.GetFaceId(q.face) + (q.corner < 0 ? 0 : q.corner);
            Far::PatchTable::PatchHandle const *handle = patchMap.FindPatch(ptexFace, q.u, q.v);
            if (!handle) {
                std::printf("none 0 0 0 0\n");
                continue;
            }
            Far::PatchDescriptor descr = table->GetPatchDescriptor(*handle);
            Far::ConstIndexArray cvs = table->GetPatchVertices(*handle);
            Far::PatchParam param = table->GetPatchParam(*handle);
            if ((int)w.size() < cvs.size()) w.resize(cvs.size());
            table->EvaluateBasis(*handle, q.u, q.v, w.data());
            Point x;
            x.Clear();
            bool exact = descr.GetType() == Far::PatchDescriptor::REGULAR;
            for (int i = 0; i < cvs.size(); ++i) {
                if (cvs[i] >= nRefined) exact = false;
                x.AddWithWeight(verts[cvs[i]], w[i]);
            }
            std::printf("%s ", exact ? "ok" : "irregular");
            printPoint(x);
            std::printf(" %d\n", (int)param.GetDepth());
        }
        checkErrors("evaluating patches");
    }

    // ---- vertex limits: uniform refinement until the sharpness at the
    // queried vertices has decayed, then the limit masks of the last level.
    if (nl > 0) {
        std::unique_ptr<Far::TopologyRefiner> refiner(Factory::Create(desc, factoryOptions));
        if (!refiner) fail("TopologyRefinerFactory rejected the mesh");
        checkErrors("creating the refiner");
        float maxSharp = 0.0f;
        for (int v : limits) maxSharp = std::max(maxSharp, vertexMaxSharp[v]);
        // At least one level: OpenSubdiv's Catmark limit masks assume all
        // incident faces are quads (wrong next to a base-level n-gon).
        int levels = std::max(1, (int)std::ceil(maxSharp));
        Far::TopologyRefiner::UniformOptions uniform(levels);
        uniform.fullTopologyInLastLevel = true;
        refiner->RefineUniform(uniform);
        checkErrors("refining uniformly");
        std::vector<Point> current(base), next;
        std::vector<int> descendant(limits);
        Far::PrimvarRefinerReal<double> primvar(*refiner);
        for (int level = 1; level <= refiner->GetMaxLevel(); ++level) {
            next.assign(refiner->GetLevel(level).GetNumVertices(), Point());
            primvar.Interpolate(level, current, next);
            Vtr::internal::Refinement const &r = refiner->getRefinement(level - 1);
            for (int &d : descendant) d = r.getVertexChildVertex(d);
            current.swap(next);
        }
        std::vector<Point> limit(current.size());
        primvar.Limit(current, limit);
        checkErrors("computing limit positions");
        for (int d : descendant) {
            printPoint(limit[d]);
            std::printf("\n");
        }
    }
    // ---- face-varying UVs: FVAR_LINEAR_ALL, a face-varying patch table,
    // the UV at each query's ptex point (after the positions and limits).
    if (nuv > 0 && nq > 0) {
        Far::TopologyDescriptor::FVarChannel channel;
        channel.numValues = nuv;
        channel.valueIndices = uvIndices.data();
        Far::TopologyDescriptor fdesc = desc;
        fdesc.numFVarChannels = 1;
        fdesc.fvarChannels = &channel;
        Sdc::Options fvarOptions = sdcOptions;
        fvarOptions.SetFVarLinearInterpolation(Sdc::Options::FVAR_LINEAR_ALL);
        Factory::Options fvarFactory(Sdc::SCHEME_CATMARK, fvarOptions);
        fvarFactory.validateFullTopology = true;
        std::unique_ptr<Far::TopologyRefiner> refiner(Factory::Create(fdesc, fvarFactory));
        if (!refiner) fail("TopologyRefinerFactory rejected the mesh with UVs");
        checkErrors("creating the refiner with UVs");

        Far::PatchTableFactory::Options patchOptions(isolation);
        patchOptions.SetPatchPrecision<double>();
        patchOptions.SetFVarPatchPrecision<double>();
        patchOptions.useInfSharpPatch = true;
        patchOptions.useSingleCreasePatch = false;
        patchOptions.generateLegacySharpCornerPatches = false;
        patchOptions.SetEndCapType(Far::PatchTableFactory::Options::ENDCAP_GREGORY_BASIS);
        patchOptions.generateFVarTables = true;
        patchOptions.generateVaryingTables = false;
        Far::TopologyRefiner::AdaptiveOptions adaptive = patchOptions.GetRefineAdaptiveOptions();
        adaptive.useInfSharpPatch = true;
        adaptive.useSingleCreasePatch = false;
        adaptive.considerFVarChannels = true;
        refiner->RefineAdaptive(adaptive);
        checkErrors("refining adaptively with UVs");
        std::unique_ptr<Far::PatchTable> table(Far::PatchTableFactory::Create(*refiner, patchOptions));
        if (!table) fail("PatchTableFactory failed with UVs");
        checkErrors("creating the patch table with UVs");

        int nRefined = refiner->GetNumFVarValuesTotal(0);
        int nLocal = table->GetNumLocalPointsFaceVarying(0);
        std::vector<Uv> values(nRefined + nLocal);
        for (int i = 0; i < nuv; ++i) values[i] = uvs[i];
        Far::PrimvarRefinerReal<double> primvar(*refiner);
        Uv *src = values.data();
        for (int level = 1; level < refiner->GetNumLevels(); ++level) {
            Uv *dst = src + refiner->GetLevel(level - 1).GetNumFVarValues(0);
            primvar.InterpolateFaceVarying(level, src, dst, 0);
            src = dst;
        }
        if (nLocal > 0) {
            Far::StencilTableReal<double> const *stencils =
                table->GetLocalPointFaceVaryingStencilTable<double>(0);
            if (!stencils) fail("no double face-varying local point stencil table");
            stencils->UpdateValues(values.data(), values.data() + nRefined);
        }
        checkErrors("interpolating UVs");

        Far::PtexIndices ptex(*refiner);
        Far::PatchMap patchMap(*table);
        std::vector<double> w(20);
        for (auto const &q : queries) {
            int ptexFace = ptex.GetFaceId(q.face) + (q.corner < 0 ? 0 : q.corner);
            Far::PatchTable::PatchHandle const *handle = patchMap.FindPatch(ptexFace, q.u, q.v);
            if (!handle) {
                std::printf("uv none 0 0\n");
                continue;
            }
            Far::ConstIndexArray cvs = table->GetPatchFVarValues(*handle, 0);
            if ((int)w.size() < cvs.size()) w.resize(cvs.size());
            table->EvaluateBasisFaceVarying(*handle, q.u, q.v, w.data(), 0, 0, 0, 0, 0, 0);
            Uv x;
            x.Clear();
            for (int i = 0; i < cvs.size(); ++i) x.AddWithWeight(values[cvs[i]], w[i]);
            std::printf("uv ok %.17g %.17g\n", x.p[0], x.p[1]);
        }
        checkErrors("evaluating UVs");
    }
    std::fflush(stdout);
    return 0;
}
