/*
 * capdiv from C: refines the sample polar net (C²PS steps, pole
 * jet) and the sample EG c-nets (steps, ring patches) through capdiv.h, in
 * float and double, and prints every input and output over semihosting as
 * the hex bits of the numbers, one line per call:
 *
 *   polar <prec> <id> <valence> <coords_len> <pole> <coords...>
 *   cnet <prec> <id> <nodes_len> <center> <nodes...>
 *   c2ps_refine <prec> <id> <coords_len> <steps> <plain> <work_len> <out_len> <status> <out...>
 *   c2ps_jet <prec> <id> <coords_len> <steps> <plain> <work_len> <status> <out...>
 *   eg_refine <prec> <id> <nodes_len> <steps> <out_len> <status> <out...>
 *   eg_ring <prec> <id> <nodes_len> <steps> <out_len> <status> <out...>
 *   badbuf <what> <status>
 *   lens <work_len(6, d)> <out_len(6, d)> <eg_refine_len(5)> <eg_ring_len(5)> <three overflows: 0>
 *   abi <calls referenced>
 *   stackphase <phase> <high-water mark of that phase>
 *   stack <high-water mark> <stack size>
 *   done <failures>
 *
 * <prec> is f32 (8 hex digits per number) or f64 (16); <id> names the
 * input (polar or cnet line) a call uses, of which it takes the first
 * <coords_len> / <nodes_len> numbers. The host test
 * (embedded-tests/tests/c_firmware_qemu.rs) recomputes every call with the
 * f64 kernel. Board: CFW_M0 (micro:bit, Cortex-M0, 16 KiB RAM) or else the
 * MPS2-AN386 (Cortex-M4F, 256 KiB claimed); CFW_F32_ONLY=1: no double calls.
 */
#include <stddef.h>
#include <stdint.h>

#include "../capi/include/capdiv.h"
#include "sample.h"
#include "semihost.h"

uint32_t stack_high_water(void);
uint32_t stack_size(void);
void stack_repaint(void);

static uint32_t stack_peak;

/* Reports the stack high-water mark of the phase just run, and repaints. */
static void phase(const char *name) {
    uint32_t used = stack_high_water();
    if (used > stack_peak) stack_peak = used;
    out_str("stackphase ");
    out_str(name);
    out_char(' ');
    out_u32(used);
    out_char('\n');
    stack_repaint();
}

/* CFW_F32_ONLY: the float calls only (what a firmware that needs no double pays). */
#ifndef CFW_F32_ONLY
#define CFW_F32_ONLY 0
#endif

#if defined(CFW_M0)
/* 16 KiB of RAM: float to depth 3, double to depth 2, no double EG (its
   subdivision alone takes about 9 KiB of stack). */
#define C2PS_STEPS_F32 3
#define C2PS_STEPS_F64 2
#define EG_F64 0
#define SCRATCH_DOUBLES 800
#else
#define C2PS_STEPS_F32 6
#define C2PS_STEPS_F64 6
#define EG_F64 1
/* double to depth 6: 6528 + 5765 doubles; float only: as many floats. */
#define SCRATCH_DOUBLES (CFW_F32_ONLY ? 6150 : 12300)
#endif
#define EG_STEPS 4

/* Work and output buffers of every call, one after the other. */
static union {
    float f[2 * SCRATCH_DOUBLES];
    double d[SCRATCH_DOUBLES];
} scratch;

static int failures;

static void expect(int ok, const char *what) {
    if (!ok) {
        ++failures;
        out_str("failed ");
        out_str(what);
        out_char('\n');
    }
}

static void head(const char *call, const char *prec, uint32_t id) {
    out_str(call);
    out_char(' ');
    out_str(prec);
    out_char(' ');
    out_u32(id);
}

static void arg(uint32_t v) {
    out_char(' ');
    out_u32(v);
}

static void status(int32_t s) {
    out_char(' ');
    out_i32(s);
}

static void floats(const float *x, size_t n) {
    for (size_t i = 0; i < n; ++i) out_f32(x[i]);
}

#if !CFW_F32_ONLY
static void doubles(const double *x, size_t n) {
    for (size_t i = 0; i < n; ++i) out_f64(x[i]);
}
#endif

static void end_line(void) { out_char('\n'); }

/* ---- float ---- */

static float pole32[3], coords32[SAMPLE_LINKS * SAMPLE_VALENCE * 3];
static float center32[3], nodes32[5 * 6 * 3];

static void to_f32(float *dst, const double *src, size_t n) {
    for (size_t i = 0; i < n; ++i) dst[i] = (float)src[i];
}

static void polar_f32(uint32_t id, size_t valence, size_t coords_len) {
    head("polar", "f32", id);
    arg(valence);
    arg(coords_len);
    floats(pole32, 3);
    floats(coords32, coords_len);
    end_line();
}

/* C²PS refine and jet of the configuration in pole32/coords32; returns the refine status. */
static int32_t c2ps_f32(uint32_t id, size_t valence, size_t coords_len, uint32_t steps,
                        uint32_t plain, size_t work_len) {
    size_t out_len = capdiv_c2ps_out_len(valence, steps);
    float *work = scratch.f, *out = scratch.f + work_len;
    int32_t s = capdiv_c2ps_refine_f32(pole32, coords32, coords_len, valence, steps, plain, work,
                                       work_len, out, out_len);
    head("c2ps_refine", "f32", id);
    arg(coords_len);
    arg(steps);
    arg(plain);
    arg(work_len);
    arg(out_len);
    status(s);
    if (s > 0) floats(out, (size_t)s);
    end_line();
    int32_t j = capdiv_c2ps_jet_f32(pole32, coords32, coords_len, valence, steps, plain, work,
                                    work_len, out, CAPDIV_JET_LEN);
    head("c2ps_jet", "f32", id);
    arg(coords_len);
    arg(steps);
    arg(plain);
    arg(work_len);
    status(j);
    if (j > 0) floats(out, (size_t)j);
    end_line();
    return s;
}

static void cnet_f32(uint32_t id, size_t nodes_len) {
    head("cnet", "f32", id);
    arg(nodes_len);
    floats(center32, 3);
    floats(nodes32, nodes_len);
    end_line();
}

/* EG refine and ring of the c-net in center32/nodes32; returns the refine status. */
static int32_t eg_f32(uint32_t id, size_t nodes_len, uint32_t steps) {
    size_t n = nodes_len / 18;
    size_t out_len = capdiv_eg_ring_len(n);
    float *out = scratch.f;
    int32_t s = capdiv_eg_refine_f32(center32, nodes32, nodes_len, steps, out, out_len);
    head("eg_refine", "f32", id);
    arg(nodes_len);
    arg(steps);
    arg(out_len);
    status(s);
    if (s > 0) floats(out, (size_t)s);
    end_line();
    int32_t r = capdiv_eg_ring_f32(center32, nodes32, nodes_len, steps, out, out_len);
    head("eg_ring", "f32", id);
    arg(nodes_len);
    arg(steps);
    arg(out_len);
    status(r);
    if (r > 0) floats(out, (size_t)r);
    end_line();
    return s;
}

static void run_f32(void) {
    const size_t v = SAMPLE_VALENCE, all = SAMPLE_LINKS * SAMPLE_VALENCE * 3;
    size_t work = capdiv_c2ps_work_len(v, C2PS_STEPS_F32);
    expect(work + capdiv_c2ps_out_len(v, C2PS_STEPS_F32) <= 2 * SCRATCH_DOUBLES, "f32 scratch");

    to_f32(pole32, SAMPLE_POLE, 3);
    to_f32(coords32, SAMPLE_COORDS, all);
    polar_f32(0, v, all);
    expect(c2ps_f32(0, v, all, C2PS_STEPS_F32, 0, work) > 0, "c2ps f32 uniform");
    expect(c2ps_f32(0, v, all, 2, 1, capdiv_c2ps_work_len(v, 2)) > 0, "c2ps f32 plain");
    /* The 2 given links only: refine works, rings need 5 links later. */
    expect(c2ps_f32(0, v, 2 * v * 3, 1, 0, capdiv_c2ps_work_len(v, 1)) > 0, "c2ps f32 2 links");
    /* Errors: a work buffer one step short; a ragged list; a NaN. */
    expect(c2ps_f32(0, v, all, 3, 0, capdiv_c2ps_work_len(v, 2)) == CAPDIV_ERR_CAPACITY_EXCEEDED,
           "c2ps f32 capacity");
    expect(c2ps_f32(0, v, all - 1, 1, 0, work) == CAPDIV_ERR_WRONG_LENGTH, "c2ps f32 ragged");
    coords32[7] = __builtin_nanf("");
    polar_f32(1, v, all);
    expect(c2ps_f32(1, v, all, 1, 0, work) == CAPDIV_ERR_NON_FINITE, "c2ps f32 nan");
    to_f32(coords32, SAMPLE_COORDS, all);

    phase("c2ps_f32");

    to_f32(center32, SAMPLE_EG_CENTER, 3);
    to_f32(nodes32, SAMPLE_EG_NODES_3, 3 * 18);
    cnet_f32(3, 3 * 18);
    expect(eg_f32(3, 3 * 18, EG_STEPS) > 0, "eg f32 n=3");
    expect(eg_f32(3, 3 * 18, 0) > 0, "eg f32 n=3, no step");
    to_f32(nodes32, SAMPLE_EG_NODES_5, 5 * 18);
    cnet_f32(5, 5 * 18);
    expect(eg_f32(5, 5 * 18, EG_STEPS) > 0, "eg f32 n=5");
    /* Errors: two sectors; a ragged node list. */
    cnet_f32(2, 2 * 18);
    expect(eg_f32(2, 2 * 18, 1) == CAPDIV_ERR_VALENCE_TOO_SMALL, "eg f32 n=2");
    expect(eg_f32(5, 5 * 18 - 1, 1) == CAPDIV_ERR_WRONG_LENGTH, "eg f32 ragged");

    /* Null buffers. */
    int32_t s = capdiv_c2ps_refine_f32(pole32, coords32, all, v, 1, 0, scratch.f, work, NULL, 100);
    out_str("badbuf c2ps_out");
    status(s);
    end_line();
    expect(s == CAPDIV_BAD_BUFFER, "null out");
    s = capdiv_c2ps_jet_f32(pole32, coords32, all, v, 1, 0, NULL, work, scratch.f, 25);
    out_str("badbuf c2ps_work");
    status(s);
    end_line();
    expect(s == CAPDIV_BAD_BUFFER, "null work");
    s = capdiv_eg_ring_f32(NULL, nodes32, 5 * 18, 1, scratch.f, 2 * SCRATCH_DOUBLES);
    out_str("badbuf eg_center");
    status(s);
    end_line();
    expect(s == CAPDIV_BAD_BUFFER, "null center");
    /* An output one short of the refined net (valence 12, 5 links: 185). */
    s = capdiv_c2ps_refine_f32(pole32, coords32, all, v, 1, 0, scratch.f, work,
                               scratch.f + work, capdiv_c2ps_out_len(v, 1) - 1);
    out_str("badbuf c2ps_short_out");
    status(s);
    end_line();
    expect(s == CAPDIV_BAD_BUFFER, "short out");

    /* The length helpers, and 0 where a length would overflow. */
    out_str("lens");
    arg(capdiv_c2ps_work_len(v, C2PS_STEPS_F32));
    arg(capdiv_c2ps_out_len(v, C2PS_STEPS_F32));
    arg(capdiv_eg_refine_len(5));
    arg(capdiv_eg_ring_len(5));
    arg(capdiv_c2ps_work_len(v, 40));
    arg(capdiv_c2ps_out_len((size_t)-1, 0));
    arg(capdiv_eg_ring_len((size_t)-1));
    end_line();
    phase("eg_f32");
}

#if !CFW_F32_ONLY
/* ---- double ---- */

/* The double calls read the sample arrays in flash directly. */
static const double *const pole64 = SAMPLE_POLE, *const coords64 = SAMPLE_COORDS;
#if EG_F64
static const double *const center64 = SAMPLE_EG_CENTER;
static const double *nodes64;
#endif

static int32_t c2ps_f64(uint32_t id, size_t valence, size_t coords_len, uint32_t steps,
                        uint32_t plain) {
    size_t work_len = capdiv_c2ps_work_len(valence, steps);
    size_t out_len = capdiv_c2ps_out_len(valence, steps);
    double *work = scratch.d, *out = scratch.d + work_len;
    expect(work_len + out_len <= SCRATCH_DOUBLES, "f64 scratch");
    int32_t s = capdiv_c2ps_refine_f64(pole64, coords64, coords_len, valence, steps, plain, work,
                                       work_len, out, out_len);
    head("c2ps_refine", "f64", id);
    arg(coords_len);
    arg(steps);
    arg(plain);
    arg(work_len);
    arg(out_len);
    status(s);
    if (s > 0) doubles(out, (size_t)s);
    end_line();
    int32_t j = capdiv_c2ps_jet_f64(pole64, coords64, coords_len, valence, steps, plain, work,
                                    work_len, out, CAPDIV_JET_LEN);
    head("c2ps_jet", "f64", id);
    arg(coords_len);
    arg(steps);
    arg(plain);
    arg(work_len);
    status(j);
    if (j > 0) doubles(out, (size_t)j);
    end_line();
    return s;
}

#if EG_F64
static int32_t eg_f64(uint32_t id, size_t nodes_len, uint32_t steps) {
    size_t n = nodes_len / 18;
    size_t out_len = capdiv_eg_ring_len(n);
    double *out = scratch.d;
    int32_t s = capdiv_eg_refine_f64(center64, nodes64, nodes_len, steps, out, out_len);
    head("eg_refine", "f64", id);
    arg(nodes_len);
    arg(steps);
    arg(out_len);
    status(s);
    if (s > 0) doubles(out, (size_t)s);
    end_line();
    int32_t r = capdiv_eg_ring_f64(center64, nodes64, nodes_len, steps, out, out_len);
    head("eg_ring", "f64", id);
    arg(nodes_len);
    arg(steps);
    arg(out_len);
    status(r);
    if (r > 0) doubles(out, (size_t)r);
    end_line();
    return s;
}

static void cnet_f64(uint32_t id, size_t nodes_len) {
    head("cnet", "f64", id);
    arg(nodes_len);
    doubles(center64, 3);
    doubles(nodes64, nodes_len);
    end_line();
}
#endif

static void run_f64(void) {
    const size_t v = SAMPLE_VALENCE, all = SAMPLE_LINKS * SAMPLE_VALENCE * 3;
    head("polar", "f64", 0);
    arg(v);
    arg(all);
    doubles(pole64, 3);
    doubles(coords64, all);
    end_line();
    expect(c2ps_f64(0, v, all, C2PS_STEPS_F64, 0) > 0, "c2ps f64 uniform");
    expect(c2ps_f64(0, v, all, 2, 1) > 0, "c2ps f64 plain");
    phase("c2ps_f64");
#if EG_F64
    nodes64 = SAMPLE_EG_NODES_3;
    cnet_f64(3, 3 * 18);
    expect(eg_f64(3, 3 * 18, EG_STEPS) > 0, "eg f64 n=3");
    nodes64 = SAMPLE_EG_NODES_5;
    cnet_f64(5, 5 * 18);
    expect(eg_f64(5, 5 * 18, EG_STEPS) > 0, "eg f64 n=5");
    phase("eg_f64");
#endif
}
#endif /* !CFW_F32_ONLY */

/*
 * Every call of the header, referenced: the link-time panic check (the
 * library's panic handler calls a symbol defined nowhere) then covers the
 * whole ABI, not only the calls run here. The unsuffixed double calls keep a
 * 209 KiB work buffer on the stack and are not run on these boards.
 */
static const void *const abi[] = {
    (const void *)capdiv_c2ps_work_len, (const void *)capdiv_c2ps_out_len,
    (const void *)capdiv_eg_refine_len, (const void *)capdiv_eg_ring_len,
    (const void *)capdiv_c2ps_refine_f32, (const void *)capdiv_c2ps_jet_f32,
    (const void *)capdiv_eg_refine_f32, (const void *)capdiv_eg_ring_f32,
#if !CFW_F32_ONLY
    (const void *)capdiv_c2ps_refine_f64, (const void *)capdiv_c2ps_jet_f64,
    (const void *)capdiv_eg_refine_f64, (const void *)capdiv_eg_ring_f64,
    (const void *)capdiv_c2ps_refine, (const void *)capdiv_c2ps_jet,
    (const void *)capdiv_eg_refine, (const void *)capdiv_eg_ring,
    (const void *)capdiv_capacity,
#endif
};

int main(void) {
    out_str("start\n");
    uint32_t linked = 0;
    for (size_t i = 0; i < sizeof abi / sizeof abi[0]; ++i) {
        linked += *(const void *const volatile *)&abi[i] != 0;
    }
    out_str("abi");
    arg(linked);
    end_line();
    run_f32();
#if !CFW_F32_ONLY
    expect(capdiv_capacity() == CAPDIV_CAPACITY, "capacity");
    run_f64();
#endif
    phase("end");
    out_str("stack");
    arg(stack_peak);
    arg(stack_size());
    end_line();
    out_str("done");
    arg((uint32_t)failures);
    end_line();
    return failures;
}
