/* The engine benchmark's cases in C, compiled with the system compiler
 * (`cc -O2`) by `engine.rs` in the same run (issue 15 point 2).
 *
 * kernels CASE RUNS PERIOD_NS
 *   runs case CASE (sieve, filter, xorshift, crc32, fbs, strings) RUNS
 *   times from a cold state, each scan PERIOD_NS of PLC time after the
 *   previous (only fbs reads the time), then prints the result as
 *   `automat run --print` prints the same variables (`NAME = value`, one
 *   per line; an LREAL with 17 significant digits, so it reads back to the
 *   same bits), before them `native TEXT` (the text the Rust version of
 *   `cases.rs` returns) and after them `best_ns N`, the best run's time
 *   measured inside.
 *
 * The algorithms are those of `cases.rs`, statement for statement; the
 * standard TON, R_TRIG and CTU are those of `sema/src/stdlib/fbs.st`.
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define SIEVE_N 200000
#define FILTER_N 1000000
#define PRNG_N 1000000
#define CRC_N 100000
#define FB_COUNT 1000
#define FB_SCANS 10000
#define STR_N 20000

/* Keeps the compiler from folding a run away: results go through here. */
static volatile uint64_t sink;

static char out[256];

static void sieve(void) {
    static unsigned char flags[SIEVE_N + 1];
    for (int32_t i = 0; i <= SIEVE_N; i++) flags[i] = 1;
    flags[0] = 0;
    flags[1] = 0;
    int32_t i = 2;
    while (i * i <= SIEVE_N) {
        if (flags[i]) {
            int32_t j = i * i;
            while (j <= SIEVE_N) {
                flags[j] = 0;
                j += i;
            }
        }
        i++;
    }
    int32_t count = 0;
    for (i = 0; i <= SIEVE_N; i++)
        if (flags[i]) count++;
    sink = count;
    snprintf(out, sizeof out, "native %d\nSIEVE.COUNT = %d\n", count, count);
}

static void filter(void) {
    double x = 0.0, y = 0.0, sum = 0.0;
    for (int32_t i = 1; i <= FILTER_N; i++) {
        x = x + 0.5;
        if (x > 100.0) x = x - 200.0;
        y = y + 0.01 * (x - y);
        sum = sum + y * y;
    }
    sink = (uint64_t)sum;
    uint64_t bits;
    memcpy(&bits, &sum, sizeof bits);
    snprintf(out, sizeof out, "native %016llx\nFILTER.SUM = %.17g\n", (unsigned long long)bits, sum);
}

static uint32_t rol(uint32_t v, int n) { return (v << n) | (v >> (32 - n)); }

static void xorshift(void) {
    uint32_t x = 0x2545F491u, acc = 0;
    for (int32_t i = 1; i <= PRNG_N; i++) {
        x ^= x << 13;
        x ^= x >> 17;
        x ^= x << 5;
        acc = rol(acc, 1) ^ x;
    }
    sink = acc;
    snprintf(out, sizeof out, "native %08x\nPRNG.ACC = %u\n", acc, acc);
}

static void crc32(void) {
    uint32_t crc = 0xFFFFFFFFu, b = 0;
    for (int32_t i = 1; i <= CRC_N; i++) {
        b = rol(b ^ 0x3Bu, 1) & 0xFFu;
        crc ^= b;
        for (int32_t k = 1; k <= 8; k++) {
            if ((crc & 1u) == 1u)
                crc = (crc >> 1) ^ 0xEDB88320u;
            else
                crc = crc >> 1;
        }
    }
    crc ^= 0xFFFFFFFFu;
    sink = crc;
    /* `CRC` alone: in program Crc, `CRC.CRC` names the variable crc first. */
    snprintf(out, sizeof out, "native %08x\nCRC = %u\n", crc, crc);
}

struct ton { int q, m; int64_t et, start; };
struct rtrig { int q, m; };
struct ctu { int cu_m, q; int16_t cv; };

static void ton_call(struct ton *t, int in, int64_t pt, int64_t now) {
    if (in) {
        if (!t->m) t->start = now;
        if (!t->q) {
            t->et = now - t->start;
            if (t->et >= pt) {
                t->et = pt;
                t->q = 1;
            }
        }
    } else {
        t->q = 0;
        t->et = 0;
    }
    t->m = in;
}

static void rtrig_call(struct rtrig *e, int clk) {
    e->q = clk && !e->m;
    e->m = clk;
}

static void ctu_call(struct ctu *c, int cu, int r, int16_t pv) {
    int edge = cu && !c->cu_m;
    c->cu_m = cu;
    if (r)
        c->cv = 0;
    else if (edge && c->cv < 32767)
        c->cv++;
    c->q = c->cv >= pv;
}

static int64_t period_ns = 1000000;

static void fbs(void) {
    static struct ton t[FB_COUNT];
    static struct rtrig e[FB_COUNT];
    static struct ctu c[FB_COUNT];
    memset(t, 0, sizeof t);
    memset(e, 0, sizeof e);
    memset(c, 0, sizeof c);
    for (int32_t scan = 0; scan < FB_SCANS; scan++) {
        int64_t now = scan * period_ns;
        for (int i = 0; i < FB_COUNT; i++) {
            ton_call(&t[i], !t[i].q, 5000000, now);
            rtrig_call(&e[i], t[i].q);
            ctu_call(&c[i], e[i].q, 0, 30000);
        }
        /* one scan's results are visible to the next only through memory */
        __asm__ volatile("" ::: "memory");
    }
    sink = (uint64_t)c[0].cv;
    /* TIME prints as automat prints it (ET <= PT = 5 ms, whole ms here):
       T#0s, else T#<n>ms. */
    char et[32];
    if (t[499].et == 0)
        snprintf(et, sizeof et, "T#0s");
    else
        snprintf(et, sizeof et, "T#%lldms", (long long)(t[499].et / 1000000));
    snprintf(out, sizeof out,
             "native %d %d %lld\nFBS.C[1].CV = %d\nFBS.C[%d].CV = %d\nFBS.T[500].ET = %s\n",
             c[0].cv, c[FB_COUNT - 1].cv, (long long)t[499].et, c[0].cv, FB_COUNT,
             c[FB_COUNT - 1].cv, et);
}

static void strings(void) {
    char s[64] = "";
    int32_t total = 0;
    for (int16_t i = 1; i <= STR_N; i++) {
        char left[32];
        size_t n = strlen(s);
        if (n > 20) n = 20;
        memcpy(left, s, n);
        left[n] = 0;
        snprintf(s, sizeof s, "%s%d", left, i);
        total += (int32_t)strlen(s);
    }
    sink = (uint64_t)total;
    snprintf(out, sizeof out, "native %d %s\nSTRS.TOTAL = %d\nSTRS.S = '%s'\n", total, s, total, s);
}

static int64_t now_ns(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (int64_t)ts.tv_sec * 1000000000 + ts.tv_nsec;
}

int main(int argc, char **argv) {
    if (argc != 4) {
        fprintf(stderr, "usage: kernels CASE RUNS PERIOD_NS\n");
        return 2;
    }
    static const struct { const char *name; void (*run)(void); } cases[] = {
        {"sieve", sieve}, {"filter", filter}, {"xorshift", xorshift},
        {"crc32", crc32}, {"fbs", fbs},       {"strings", strings},
    };
    void (*run)(void) = 0;
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++)
        if (strcmp(argv[1], cases[i].name) == 0) run = cases[i].run;
    if (!run) {
        fprintf(stderr, "unknown case %s\n", argv[1]);
        return 2;
    }
    int runs = atoi(argv[2]);
    period_ns = atoll(argv[3]);
    int64_t best = INT64_MAX;
    for (int r = 0; r < (runs < 1 ? 1 : runs); r++) {
        int64_t t0 = now_ns();
        run();
        int64_t d = now_ns() - t0;
        if (d < best) best = d;
    }
    fputs(out, stdout);
    printf("best_ns %lld\n", (long long)best);
    return 0;
}
