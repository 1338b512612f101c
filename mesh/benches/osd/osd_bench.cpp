// OpenSubdiv 3.5's side of mesh/benches/osd_side_by_side.rs: the analysis of
// one tagged mesh (the job format of mesh/tests/osd/oracle.cpp, read from the
// file named on the command line; queries and limits are ignored) timed stage
// by stage, and the patches it makes.
//
//   osd-bench JOB        time it and print one "key value" line per result
//   osd-bench --once JOB run the analysis once (for callgrind, which counts
//                        only inside analyse() with --toggle-collect=analyse*)
//
// The analysis is what a renderer does before it sees positions:
// TopologyRefinerFactory::Create (with the creases, corners and holes),
// RefineAdaptive to the isolation level (infinitely sharp patches on, single
// crease patches off, as the oracle), PatchTableFactory::Create (Gregory
// basis end caps) and a PatchMap for locating ptex points.
//
// Build: g++ -O2 -std=c++14 osd_bench.cpp -o osd-bench -losdCPU

#include <opensubdiv/far/patchMap.h>
#include <opensubdiv/far/patchTable.h>
#include <opensubdiv/far/patchTableFactory.h>
#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/far/topologyRefinerFactory.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
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

void onWarning(const char *) {}

[[noreturn]] void fail(const char *what) {
    std::fprintf(stderr, "osd-bench: %s\n", what);
    std::exit(2);
}

struct Mesh {
    int nv = 0, nf = 0;
    std::vector<int> vertsPerFace;
    std::vector<Far::Index> faceVerts;
    std::vector<Far::Index> creaseVerts;
    std::vector<float> creaseWeights;
    std::vector<Far::Index> cornerVerts;
    std::vector<float> cornerWeights;
    std::vector<Far::Index> holes;
    Sdc::Options sdc;
    int isolation = 4;
};

int header(std::istream &in, const char *key) {
    std::string word;
    long n = -1;
    if (!(in >> word) || word != key || !(in >> n) || n < 0) fail(key);
    return (int)n;
}

std::string keyword(std::istream &in, const char *key) {
    std::string word, value;
    if (!(in >> word) || word != key || !(in >> value)) fail(key);
    return value;
}

Mesh readJob(const char *path) {
    std::ifstream in(path);
    if (!in) fail("cannot open the job file");
    Mesh m;
    m.nv = header(in, "vertices");
    double coordinate;
    for (int i = 0; i < 3 * m.nv; ++i)
        if (!(in >> coordinate)) fail("vertex coordinate");
    m.nf = header(in, "faces");
    m.vertsPerFace.resize(m.nf);
    for (int f = 0; f < m.nf; ++f) {
        int k;
        if (!(in >> k) || k < 3) fail("face size");
        m.vertsPerFace[f] = k;
        for (int i = 0; i < k; ++i) {
            int v;
            if (!(in >> v) || v < 0 || v >= m.nv) fail("face vertex");
            m.faceVerts.push_back(v);
        }
    }
    int nc = header(in, "creases");
    for (int i = 0; i < nc; ++i) {
        int a, b;
        float s;
        if (!(in >> a >> b >> s)) fail("crease");
        m.creaseVerts.push_back(a);
        m.creaseVerts.push_back(b);
        m.creaseWeights.push_back(s);
    }
    int nk = header(in, "corners");
    for (int i = 0; i < nk; ++i) {
        int v;
        float s;
        if (!(in >> v >> s)) fail("corner");
        m.cornerVerts.push_back(v);
        m.cornerWeights.push_back(s);
    }
    int nh = header(in, "holes");
    for (int i = 0; i < nh; ++i) {
        int f;
        if (!(in >> f)) fail("hole");
        m.holes.push_back(f);
    }
    std::string boundary = keyword(in, "boundary");
    if (boundary == "none")
        m.sdc.SetVtxBoundaryInterpolation(Sdc::Options::VTX_BOUNDARY_NONE);
    else if (boundary == "edge-only")
        m.sdc.SetVtxBoundaryInterpolation(Sdc::Options::VTX_BOUNDARY_EDGE_ONLY);
    else
        m.sdc.SetVtxBoundaryInterpolation(Sdc::Options::VTX_BOUNDARY_EDGE_AND_CORNER);
    std::string creasing = keyword(in, "creasing");
    m.sdc.SetCreasingMethod(creasing == "chaikin" ? Sdc::Options::CREASE_CHAIKIN
                                                  : Sdc::Options::CREASE_UNIFORM);
    std::string triangles = keyword(in, "triangles");
    m.sdc.SetTriangleSubdivision(triangles == "smooth" ? Sdc::Options::TRI_SUB_SMOOTH
                                                       : Sdc::Options::TRI_SUB_CATMARK);
    m.isolation = std::atoi(keyword(in, "isolation").c_str());
    if (m.isolation < 1 || m.isolation > 10) fail("isolation");
    return m;
}

// Seconds spent in each stage of one analysis.
struct Stages {
    double create = 0, refine = 0, table = 0, map = 0;
};

struct Result {
    std::unique_ptr<Far::TopologyRefiner> refiner;
    std::unique_ptr<Far::PatchTable> table;
    std::unique_ptr<Far::PatchMap> map;
};

typedef std::chrono::steady_clock Clock;

double since(Clock::time_point &t) {
    Clock::time_point now = Clock::now();
    double s = std::chrono::duration<double>(now - t).count();
    t = now;
    return s;
}

}  // namespace

// The measured analysis (not inlined, so that callgrind can count it alone).
extern "C" __attribute__((noinline)) void analyse(Mesh const &m, Result &r, Stages &s) {
    Far::TopologyDescriptor desc;
    desc.numVertices = m.nv;
    desc.numFaces = m.nf;
    desc.numVertsPerFace = m.vertsPerFace.data();
    desc.vertIndicesPerFace = m.faceVerts.data();
    desc.numCreases = (int)m.creaseWeights.size();
    desc.creaseVertexIndexPairs = m.creaseVerts.data();
    desc.creaseWeights = m.creaseWeights.data();
    desc.numCorners = (int)m.cornerWeights.size();
    desc.cornerVertexIndices = m.cornerVerts.data();
    desc.cornerWeights = m.cornerWeights.data();
    desc.numHoles = (int)m.holes.size();
    desc.holeIndices = m.holes.data();

    Clock::time_point t = Clock::now();
    typedef Far::TopologyRefinerFactory<Far::TopologyDescriptor> Factory;
    Factory::Options factoryOptions(Sdc::SCHEME_CATMARK, m.sdc);
    r.refiner.reset(Factory::Create(desc, factoryOptions));
    if (!r.refiner) fail("TopologyRefinerFactory rejected the mesh");
    s.create += since(t);

    Far::PatchTableFactory::Options patchOptions(m.isolation);
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
    r.refiner->RefineAdaptive(adaptive);
    s.refine += since(t);

    r.table.reset(Far::PatchTableFactory::Create(*r.refiner, patchOptions));
    if (!r.table) fail("PatchTableFactory failed");
    s.table += since(t);

    r.map.reset(new Far::PatchMap(*r.table));
    s.map += since(t);
}

int main(int argc, char **argv) {
    Far::SetErrorCallback(onError);
    Far::SetWarningCallback(onWarning);
    bool once = argc == 3 && std::strcmp(argv[1], "--once") == 0;
    if (!once && argc != 2) fail("usage: osd-bench [--once] JOB");
    Mesh m = readJob(argv[argc - 1]);

    if (once) {
        Result r;
        Stages s;
        analyse(m, r, s);
        if (g_error) fail("OpenSubdiv reported an error");
        std::printf("patches %d\n", r.table->GetNumPatchesTotal());
        return 0;
    }

    // Batches of `batch` analyses, `batch` doubled until one takes 2 ms;
    // then samples until about 2 s are spent (5..21 samples). Per stage and
    // in total, the median over samples of the time per analysis.
    auto runBatch = [&](int batch, Stages &s) {
        for (int i = 0; i < batch; ++i) {
            Result r;
            analyse(m, r, s);
        }
    };
    int batch = 1;
    double batchTime;
    for (;;) {
        Stages s;
        Clock::time_point t = Clock::now();
        runBatch(batch, s);
        batchTime = since(t);
        if (batchTime >= 2e-3 || batch >= (1 << 20)) break;
        batch *= 2;
    }
    int samples = std::max(5, std::min(21, (int)(2.0 / batchTime)));
    std::vector<double> create, refine, table, map, total;
    for (int k = 0; k < samples; ++k) {
        Stages s;
        Clock::time_point t = Clock::now();
        runBatch(batch, s);
        double all = since(t);
        create.push_back(s.create / batch);
        refine.push_back(s.refine / batch);
        table.push_back(s.table / batch);
        map.push_back(s.map / batch);
        total.push_back(all / batch);
    }
    if (g_error) fail("OpenSubdiv reported an error");
    auto median = [](std::vector<double> v) {
        std::sort(v.begin(), v.end());
        return v[v.size() / 2];
    };
    std::printf("samples %d\nbatch %d\n", samples, batch);
    std::printf("create_ns %.1f\n", 1e9 * median(create));
    std::printf("refine_ns %.1f\n", 1e9 * median(refine));
    std::printf("table_ns %.1f\n", 1e9 * median(table));
    std::printf("map_ns %.1f\n", 1e9 * median(map));
    std::printf("total_ns %.1f\n", 1e9 * median(total));
    std::printf("total_min_ns %.1f\n", 1e9 * *std::min_element(total.begin(), total.end()));

    // The patches: in total, by type and by depth (PatchParam::GetDepth:
    // refinement levels below the base face; the ptex sub-faces of a
    // non-quad face start at depth 1).
    Result r;
    Stages s;
    analyse(m, r, s);
    Far::PatchTable const &pt = *r.table;
    std::map<int, int> byDepth;
    int regular = 0, irregular = 0;
    for (int a = 0; a < pt.GetNumPatchArrays(); ++a) {
        bool isRegular = pt.GetPatchArrayDescriptor(a).GetType() == Far::PatchDescriptor::REGULAR;
        for (int p = 0; p < pt.GetNumPatches(a); ++p) {
            ++byDepth[pt.GetPatchParam(a, p).GetDepth()];
            ++(isRegular ? regular : irregular);
        }
    }
    std::printf("patches %d\nregular %d\nendcap %d\n", pt.GetNumPatchesTotal(), regular, irregular);
    for (auto const &d : byDepth) std::printf("depth%d %d\n", d.first, d.second);
    return 0;
}
