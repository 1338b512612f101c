// OpenSubdiv 3.5's side of mesh/benches/osd_side_by_side.rs and
// mesh/benches/osd_whole_job.rs: the analysis of one tagged mesh (the job
// format of mesh/tests/osd/oracle.cpp, read from the file named on the
// command line; queries and limits are ignored) timed stage by stage, and the
// patches it makes; or the whole job (below).
//
//   osd-bench JOB        time the analysis and print one "key value" line
//                        per result
//   osd-bench --once JOB run the analysis once (for callgrind, which counts
//                        only inside analyse() with --toggle-collect=analyse*)
//   osd-bench --whole JOB [DUMP]
//                        time the whole job in f64 and in f32, print "key
//                        value" lines; DUMP: write the f64 samples there
//                        (native doubles, 6 per sample)
//   osd-bench --whole-once JOB f64|f32 [primvar]
//                        the whole job once, inside osd_whole_job_f64 or
//                        osd_whole_job_f32 (callgrind's --toggle-collect);
//                        with primvar, the refined points from PrimvarRefiner
//                        instead of stencil tables, inside
//                        osd_whole_job_primvar_f64 or _f32
//
// The whole job: mesh in, positions and unit normals out on a 5x5 grid of
// (u, v) = ((2i+1)/10, (2j+1)/10) per ptex face. As OpenSubdiv's Far
// tutorials do it: the analysis (with patches of the job's precision), a
// stencil table giving every refined vertex and every local (end-cap) point
// from the control vertices (StencilTableFactoryReal::Create with all levels,
// factorised, then AppendLocalPointStencilTable with the patch table's local
// point stencils of the same precision), the points from the stencils
// (UpdateValues), then per sample PatchMap::FindPatch,
// PatchTable::EvaluateBasis (value and first derivatives) and the sums over
// the patch's control points: position, du, dv, normal du x dv normalised.
// Re-evaluation (vertices moved, topology kept) is the points and the
// samples again.
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
#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/far/ptexIndices.h>
#include <opensubdiv/far/stencilTableFactory.h>
#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/far/topologyRefinerFactory.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>
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
    std::vector<double> coords;
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
    m.coords.resize(3 * (size_t)m.nv);
    for (double &c : m.coords)
        if (!(in >> c)) fail("vertex coordinate");
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

// The analysis with local point stencils of precision REAL.
template <typename REAL>
void analyseIn(Mesh const &m, Result &r, Stages &s) {
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
    patchOptions.SetPatchPrecision<REAL>();
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

// The measured analysis (not inlined, so that callgrind can count it alone),
// float local point stencils (PatchTableFactory's default).
extern "C" __attribute__((noinline)) void analyse(Mesh const &m, Result &r, Stages &s) {
    analyseIn<float>(m, r, s);
}

namespace {

// A point as StencilTableReal::UpdateValues and the sample sums want it.
template <typename REAL>
struct Vertex {
    REAL p[3];
    void Clear(void * = nullptr) { p[0] = p[1] = p[2] = 0; }
    void AddWithWeight(Vertex const &src, REAL w) {
        p[0] += w * src.p[0];
        p[1] += w * src.p[1];
        p[2] += w * src.p[2];
    }
};

// Samples per ptex face side; sample (i, j) of a face is at
// ((2i+1)/10, (2j+1)/10): never on a patch boundary (those are dyadic), so
// each sample lies inside exactly one patch of either library.
const int GRID = 5;

// Seconds spent in each stage of the whole job.
struct JobStages {
    Stages analysis;
    double stencils = 0, points = 0, sample = 0;
};

// The whole job's state in precision REAL.
template <typename REAL>
struct Job {
    Result r;
    // Refined vertices of every level after the first, then the local
    // points, each from the control vertices.
    std::unique_ptr<Far::StencilTableReal<REAL> const> stencils;
    int numPtex = 0;
    // Control vertices, refined vertices, local points: the indices of the
    // patch table's control points.
    std::vector<Vertex<REAL>> points;
    // Per sample: position, unit normal (NaN where no patch: holes).
    std::vector<REAL> out;
};

template <typename REAL>
__attribute__((noinline)) void buildStencils(Job<REAL> &job) {
    typedef Far::StencilTableFactoryReal<REAL> Factory;
    typename Factory::Options options;
    options.generateIntermediateLevels = true;
    options.factorizeIntermediateLevels = true;
    options.generateOffsets = true;
    Far::StencilTableReal<REAL> const *refined = Factory::Create(*job.r.refiner, options);
    Far::StencilTableReal<REAL> const *local =
        job.r.table->template GetLocalPointStencilTable<REAL>();
    if (local && local->GetNumStencils() > 0) {
        Far::StencilTableReal<REAL> const *all =
            Factory::AppendLocalPointStencilTable(*job.r.refiner, refined, local);
        delete refined;
        refined = all;
    }
    job.stencils.reset(refined);
    job.numPtex = Far::PtexIndices(*job.r.refiner).GetNumFaces();
}

template <typename REAL>
__attribute__((noinline)) void computePoints(Job<REAL> &job, std::vector<double> const &coords) {
    size_t nv = coords.size() / 3;
    size_t n = nv + (job.stencils ? job.stencils->GetNumStencils() : 0);
    job.points.resize(n);
    for (size_t i = 0; i < nv; ++i)
        for (int k = 0; k < 3; ++k) job.points[i].p[k] = (REAL)coords[3 * i + k];
    if (n > nv) job.stencils->UpdateValues(job.points.data(), job.points.data() + nv);
}

template <typename REAL>
__attribute__((noinline)) void samplePoints(Job<REAL> &job) {
    Far::PatchTable const &table = *job.r.table;
    Far::PatchMap const &map = *job.r.map;
    job.out.resize((size_t)job.numPtex * GRID * GRID * 6);
    REAL wP[20], wDu[20], wDv[20];
    REAL *o = job.out.data();
    for (int f = 0; f < job.numPtex; ++f) {
        for (int i = 0; i < GRID; ++i) {
            REAL u = REAL(2 * i + 1) / REAL(2 * GRID);
            for (int j = 0; j < GRID; ++j, o += 6) {
                REAL v = REAL(2 * j + 1) / REAL(2 * GRID);
                Far::PatchTable::PatchHandle const *h = map.FindPatch(f, u, v);
                if (!h) {
                    std::fill(o, o + 6, std::numeric_limits<REAL>::quiet_NaN());
                    continue;
                }
                table.EvaluateBasis<REAL>(*h, u, v, wP, wDu, wDv);
                Far::ConstIndexArray cvs = table.GetPatchVertices(*h);
                REAL p[3] = {0, 0, 0}, du[3] = {0, 0, 0}, dv[3] = {0, 0, 0};
                for (int c = 0; c < cvs.size(); ++c) {
                    REAL const *x = job.points[cvs[c]].p;
                    for (int k = 0; k < 3; ++k) {
                        p[k] += wP[c] * x[k];
                        du[k] += wDu[c] * x[k];
                        dv[k] += wDv[c] * x[k];
                    }
                }
                REAL n[3] = {du[1] * dv[2] - du[2] * dv[1], du[2] * dv[0] - du[0] * dv[2],
                             du[0] * dv[1] - du[1] * dv[0]};
                REAL len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
                REAL s = len > 0 ? REAL(1) / len : REAL(0);
                o[0] = p[0], o[1] = p[1], o[2] = p[2];
                o[3] = n[0] * s, o[4] = n[1] * s, o[5] = n[2] * s;
            }
        }
    }
}

template <typename REAL>
void wholeJob(Mesh const &m, Job<REAL> &job, JobStages &s) {
    analyseIn<REAL>(m, job.r, s.analysis);
    Clock::time_point t = Clock::now();
    buildStencils(job);
    s.stencils += since(t);
    computePoints(job, m.coords);
    s.points += since(t);
    samplePoints(job);
    s.sample += since(t);
}

// Re-evaluation: the same topology, vertices moved.
template <typename REAL>
void reevaluate(Job<REAL> &job, std::vector<double> const &coords) {
    computePoints(job, coords);
    samplePoints(job);
}

// Re-evaluation the other way OpenSubdiv offers (its oracle's and
// tutorial_5_1's): PrimvarRefiner::Interpolate level by level, then the
// local points from the patch table's stencils. Reported beside.
template <typename REAL>
__attribute__((noinline)) void primvarPoints(Job<REAL> &job, std::vector<double> const &coords) {
    Far::TopologyRefiner const &refiner = *job.r.refiner;
    size_t nv = coords.size() / 3;
    int nRefined = refiner.GetNumVerticesTotal();
    Far::StencilTableReal<REAL> const *local =
        job.r.table->template GetLocalPointStencilTable<REAL>();
    int nLocal = local ? local->GetNumStencils() : 0;
    job.points.resize(nRefined + nLocal);
    for (size_t i = 0; i < nv; ++i)
        for (int k = 0; k < 3; ++k) job.points[i].p[k] = (REAL)coords[3 * i + k];
    Far::PrimvarRefinerReal<REAL> primvar(refiner);
    Vertex<REAL> *src = job.points.data();
    for (int level = 1; level < refiner.GetNumLevels(); ++level) {
        Vertex<REAL> *dst = src + refiner.GetLevel(level - 1).GetNumVertices();
        primvar.Interpolate(level, src, dst);
        src = dst;
    }
    if (nLocal > 0) local->UpdateValues(job.points.data(), job.points.data() + nRefined);
}

std::vector<double> moved(std::vector<double> c) {
    for (double &x : c) x *= 1.01;
    return c;
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

// Runs `batch(n)` (n calls of the measured thing) in batches doubled until
// one takes 2 ms, then samples until about 2 s are spent (5..21 samples);
// returns the batch size and the number of samples, calls `record` after
// each sample with the batch size.
template <typename Batch, typename Record>
std::pair<int, int> timeBatches(Batch batchOf, Record record) {
    int batch = 1;
    double took;
    for (;;) {
        Clock::time_point t = Clock::now();
        batchOf(batch, false);
        took = since(t);
        if (took >= 2e-3 || batch >= (1 << 20)) break;
        batch *= 2;
    }
    int samples = std::max(5, std::min(21, (int)(2.0 / took)));
    for (int k = 0; k < samples; ++k) {
        Clock::time_point t = Clock::now();
        batchOf(batch, true);
        record(since(t) / batch, batch);
    }
    return std::make_pair(batch, samples);
}

template <typename REAL>
void measureWhole(Mesh const &m, char const *prefix, Job<REAL> &keep) {
    std::vector<double> create, refine, table, map, analysis, stencils, points, sample, total;
    JobStages s;
    std::pair<int, int> bs = timeBatches(
        [&](int n, bool timed) {
            s = JobStages();
            for (int i = 0; i < n; ++i) {
                Job<REAL> job;
                wholeJob(m, job, s);
            }
            (void)timed;
        },
        [&](double all, int n) {
            create.push_back(s.analysis.create / n);
            refine.push_back(s.analysis.refine / n);
            table.push_back(s.analysis.table / n);
            map.push_back(s.analysis.map / n);
            analysis.push_back(
                (s.analysis.create + s.analysis.refine + s.analysis.table + s.analysis.map) / n);
            stencils.push_back(s.stencils / n);
            points.push_back(s.points / n);
            sample.push_back(s.sample / n);
            total.push_back(all);
        });
    std::printf("%s_samples %d\n%s_batch %d\n", prefix, bs.second, prefix, bs.first);
    std::printf("%s_create_ns %.1f\n", prefix, 1e9 * median(create));
    std::printf("%s_refine_ns %.1f\n", prefix, 1e9 * median(refine));
    std::printf("%s_table_ns %.1f\n", prefix, 1e9 * median(table));
    std::printf("%s_map_ns %.1f\n", prefix, 1e9 * median(map));
    std::printf("%s_analysis_ns %.1f\n", prefix, 1e9 * median(analysis));
    std::printf("%s_stencils_ns %.1f\n", prefix, 1e9 * median(stencils));
    std::printf("%s_points_ns %.1f\n", prefix, 1e9 * median(points));
    std::printf("%s_sample_ns %.1f\n", prefix, 1e9 * median(sample));
    std::printf("%s_total_ns %.1f\n", prefix, 1e9 * median(total));

    // The whole job with the refined points from PrimvarRefiner (no stencil
    // tables but the patch table's local point stencils).
    std::vector<double> primvarTotal;
    timeBatches(
        [&](int n, bool) {
            for (int i = 0; i < n; ++i) {
                Job<REAL> job;
                Stages st;
                analyseIn<REAL>(m, job.r, st);
                job.numPtex = Far::PtexIndices(*job.r.refiner).GetNumFaces();
                primvarPoints(job, m.coords);
                samplePoints(job);
            }
        },
        [&](double all, int) { primvarTotal.push_back(all); });
    std::printf("%s_total_primvar_ns %.1f\n", prefix, 1e9 * median(primvarTotal));

    JobStages once;
    wholeJob(m, keep, once);
    std::vector<double> other = moved(m.coords);
    std::vector<double> reeval, primvar;
    int flip = 0;
    timeBatches(
        [&](int n, bool) {
            for (int i = 0; i < n; ++i) reevaluate(keep, (flip++ & 1) ? other : m.coords);
        },
        [&](double all, int) { reeval.push_back(all); });
    std::printf("%s_reeval_ns %.1f\n", prefix, 1e9 * median(reeval));
    timeBatches(
        [&](int n, bool) {
            for (int i = 0; i < n; ++i) {
                primvarPoints(keep, (flip++ & 1) ? other : m.coords);
                samplePoints(keep);
            }
        },
        [&](double all, int) { primvar.push_back(all); });
    std::printf("%s_reeval_primvar_ns %.1f\n", prefix, 1e9 * median(primvar));
    // Leave `keep` evaluated on the input positions.
    reevaluate(keep, m.coords);
}

}  // namespace

// The whole job once (not inlined: callgrind's --toggle-collect).
extern "C" __attribute__((noinline)) void osd_whole_job_f64(Mesh const &m, Job<double> &job) {
    JobStages s;
    wholeJob(m, job, s);
}

extern "C" __attribute__((noinline)) void osd_whole_job_f32(Mesh const &m, Job<float> &job) {
    JobStages s;
    wholeJob(m, job, s);
}

namespace {

// The whole job with the refined points from PrimvarRefiner instead of
// stencil tables.
template <typename REAL>
void wholeJobPrimvar(Mesh const &m, Job<REAL> &job) {
    Stages s;
    analyseIn<REAL>(m, job.r, s);
    job.numPtex = Far::PtexIndices(*job.r.refiner).GetNumFaces();
    primvarPoints(job, m.coords);
    samplePoints(job);
}

}  // namespace

extern "C" __attribute__((noinline)) void osd_whole_job_primvar_f64(Mesh const &m,
                                                                    Job<double> &job) {
    wholeJobPrimvar(m, job);
}

extern "C" __attribute__((noinline)) void osd_whole_job_primvar_f32(Mesh const &m,
                                                                    Job<float> &job) {
    wholeJobPrimvar(m, job);
}

// `--whole JOB [DUMP]` and `--whole-once JOB f64|f32 [primvar]`.
int whole(int argc, char **argv) {
    bool once = std::strcmp(argv[1], "--whole-once") == 0;
    if (argc < 3) fail("usage: osd-bench --whole JOB [DUMP] | --whole-once JOB f64|f32");
    Mesh m = readJob(argv[2]);
    if (once) {
        if (argc != 4 && argc != 5) fail("--whole-once JOB f64|f32 [primvar]");
        bool primvar = argc == 5 && std::strcmp(argv[4], "primvar") == 0;
        size_t covered = 0;
        if (std::strcmp(argv[3], "f64") == 0) {
            Job<double> job;
            if (primvar)
                osd_whole_job_primvar_f64(m, job);
            else
                osd_whole_job_f64(m, job);
            for (size_t k = 0; k < job.out.size(); k += 6) covered += !std::isnan(job.out[k]);
        } else {
            Job<float> job;
            if (primvar)
                osd_whole_job_primvar_f32(m, job);
            else
                osd_whole_job_f32(m, job);
            for (size_t k = 0; k < job.out.size(); k += 6) covered += !std::isnan(job.out[k]);
        }
        if (g_error) fail("OpenSubdiv reported an error");
        std::printf("covered %zu\n", covered);
        return 0;
    }
    Job<double> j64;
    Job<float> j32;
    measureWhole(m, "f64", j64);
    measureWhole(m, "f32", j32);
    if (g_error) fail("OpenSubdiv reported an error");
    // f32 against f64: largest |n32 - n64| over the samples both cover.
    size_t covered = 0;
    double worstNormal = 0, worstPosition = 0;
    for (size_t k = 0; k < j64.out.size(); k += 6) {
        if (std::isnan(j64.out[k])) continue;
        ++covered;
        double dn = 0, dp = 0;
        for (int c = 0; c < 3; ++c) {
            dp = std::max(dp, std::fabs(j64.out[k + c] - (double)j32.out[k + c]));
            double d = j64.out[k + 3 + c] - (double)j32.out[k + 3 + c];
            dn += d * d;
        }
        worstNormal = std::max(worstNormal, std::sqrt(dn));
        worstPosition = std::max(worstPosition, dp);
    }
    std::printf("ptex %d\ncovered %zu\nlocal_points %d\nstencils %d\n", j64.numPtex, covered,
                j64.r.table->GetNumLocalPoints(), j64.stencils->GetNumStencils());
    std::printf("f32_normal_err %.3e\nf32_position_err %.3e\n", worstNormal, worstPosition);
    if (argc >= 4) {
        FILE *dump = std::fopen(argv[3], "wb");
        if (!dump) fail("cannot write the dump");
        std::fwrite(j64.out.data(), sizeof(double), j64.out.size(), dump);
        std::fclose(dump);
    }
    return 0;
}

int main(int argc, char **argv) {
    Far::SetErrorCallback(onError);
    Far::SetWarningCallback(onWarning);
    if (argc >= 2 && std::strncmp(argv[1], "--whole", 7) == 0) return whole(argc, argv);
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
