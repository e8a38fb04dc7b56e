/*
 * embree_rays: the C side of the "Embree vs C" comparison (scratchwave-embree).
 *
 * Loads the same Embree 4 library as the Rust crate (dlopen of the path its build script
 * found), builds the same triangle mesh with the same settings, and traces the same rays
 * through the plain C API, single-threaded, so that the Rust wrapper's cost can be measured
 * against nothing but Embree itself.
 *
 *     embree_rays LIBRARY DEVICE_CONFIG WORKLOAD
 *
 * WORKLOAD (little-endian, written by scratchwave_embree::c_reference):
 *     char  magic[8] = "SWRAYS01"
 *     u32   vertex_count, triangle_count, ray_set_count
 *     f32   vertices[vertex_count][3]
 *     u32   indices[triangle_count][3]
 *     per ray set: u32 n; f32 rays[n][8]   (org x y z, tnear, dir x y z, tfar)
 *
 * After building the scene it prints "ready VERSION BUILD_SECONDS" (CPU seconds) and then answers one
 * command per line on stdin:
 *     run SET PATH COHERENT MIN_SECONDS MIN_PASSES BLOCK
 * with PATH one of intersect1, intersect8, intersect16, occluded1. It traces all rays of the
 * set once per pass, in blocks of BLOCK consecutive rays (a multiple of 16, so packets are
 * the same as without blocks), each block timed; passes repeat until both minimums are
 * reached. It prints
 *     ok RAYS PASSES BEST_SECONDS TOTAL_SECONDS HITS CHECKSUM
 * with BEST_SECONDS the sum over blocks of each block's fastest time (a pass without
 * interference from other processes), TOTAL_SECONDS the time of all passes (both in CPU time
 * of the tracing thread, CLOCK_THREAD_CPUTIME_ID; also MIN_SECONDS), HITS the rays hit
 * or occluded and CHECKSUM 16 hex digits of the FNV-1a hash defined below, both of the last
 * pass. "quit" or end of input exits. Errors go to stderr with exit code 1.
 *
 * No Embree header is needed: the few declarations below follow the Embree 4.4 headers
 * (RTC_MAX_INSTANCE_LEVEL_COUNT = 1, RTC_GEOMETRY_INSTANCE_ARRAY, RTC_MIN_WIDTH), the same
 * layouts as backend-embree/src/ffi.rs, with static size checks.
 */

#define _POSIX_C_SOURCE 200809L

#include <dlfcn.h>
#include <math.h>
#include <stdalign.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

/* ---- Embree 4.4 ABI (only what this program uses) ---------------------------------------- */

typedef void *Device;
typedef void *Scene;
typedef void *Geometry;

#define INVALID_ID 0xffffffffu

enum {
    ERROR_NONE = 0,
    PROPERTY_VERSION = 0,
    BUILD_QUALITY_MEDIUM = 1,
    SCENE_FLAG_NONE = 0,
    GEOMETRY_TRIANGLE = 0,
    BUFFER_INDEX = 0,
    BUFFER_VERTEX = 1,
    FORMAT_UINT3 = 0x5003,
    FORMAT_FLOAT3 = 0x9003,
    QUERY_INCOHERENT = 0,
    QUERY_COHERENT = 1 << 16,
    FEATURES_ALL = (int)0xffffffffu,
};

typedef struct {
    alignas(16) float org_x;
    float org_y, org_z, tnear;
    float dir_x, dir_y, dir_z, time;
    float tfar;
    uint32_t mask, id, flags;
} Ray1;

typedef struct {
    alignas(16) float ng_x;
    float ng_y, ng_z, u, v;
    uint32_t prim_id, geom_id, inst_id[1], inst_prim_id[1];
} Hit1;

typedef struct {
    Ray1 ray;
    Hit1 hit;
} RayHit1;

/* Structure-of-arrays packets of N lanes, aligned to 4·N bytes like Embree's. */
#define PACKET(N)                                                                           \
    typedef struct {                                                                        \
        alignas(4 * N) float org_x[N];                                                      \
        float org_y[N], org_z[N], tnear[N], dir_x[N], dir_y[N], dir_z[N], time[N], tfar[N]; \
        uint32_t mask[N], id[N], flags[N];                                                  \
    } Ray##N;                                                                               \
    typedef struct {                                                                        \
        alignas(4 * N) float ng_x[N];                                                       \
        float ng_y[N], ng_z[N], u[N], v[N];                                                 \
        uint32_t prim_id[N], geom_id[N], inst_id[1][N], inst_prim_id[1][N];                 \
    } Hit##N;                                                                               \
    typedef struct {                                                                        \
        Ray##N ray;                                                                         \
        Hit##N hit;                                                                         \
    } RayHit##N;

PACKET(8)
PACKET(16)

typedef struct {
    int flags;        /* RTCRayQueryFlags */
    int feature_mask; /* RTCFeatureFlags */
    void *context;
    void *filter;
    void *callback; /* intersect or occluded */
    float min_width_distance_factor;
} QueryArgs;

_Static_assert(sizeof(Ray1) == 48, "RTCRay");
_Static_assert(sizeof(RayHit1) == 96 && alignof(RayHit1) == 16, "RTCRayHit");
_Static_assert(sizeof(RayHit8) == 672 && alignof(RayHit8) == 32, "RTCRayHit8");
_Static_assert(sizeof(RayHit16) == 1344 && alignof(RayHit16) == 64, "RTCRayHit16");
_Static_assert(sizeof(QueryArgs) == 40, "RTCIntersectArguments");

static struct {
    Device (*new_device)(const char *);
    void (*release_device)(Device);
    long (*device_property)(Device, int);
    int (*device_error)(Device);
    const char *(*last_error_message)(Device);
    Scene (*new_scene)(Device);
    void (*release_scene)(Scene);
    void (*set_build_quality)(Scene, int);
    void (*set_scene_flags)(Scene, int);
    void (*commit_scene)(Scene);
    Geometry (*new_geometry)(Device, int);
    void *(*new_buffer)(Geometry, int, unsigned, int, size_t, size_t);
    void (*commit_geometry)(Geometry);
    unsigned (*attach)(Scene, Geometry);
    void (*release_geometry)(Geometry);
    void (*intersect1)(Scene, RayHit1 *, QueryArgs *);
    void (*intersect8)(const int *, Scene, RayHit8 *, QueryArgs *);
    void (*intersect16)(const int *, Scene, RayHit16 *, QueryArgs *);
    void (*occluded1)(Scene, Ray1 *, QueryArgs *);
} rtc;

/* ---- helpers ------------------------------------------------------------------------------ */

static void die(const char *what, const char *detail) {
    fprintf(stderr, "embree_rays: %s%s%s\n", what, detail ? ": " : "", detail ? detail : "");
    exit(1);
}

static void *symbol(void *library, const char *name) {
    void *p = dlsym(library, name);
    if (!p) die("missing symbol", name);
    return p;
}

static void check(Device device, const char *during) {
    if (rtc.device_error(device) != ERROR_NONE) die(during, rtc.last_error_message(device));
}

/* CPU time of this thread: leaves out the time spent waiting for a core. */
static double cpu_now(void) {
    struct timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static void read_exact(FILE *f, void *out, size_t bytes) {
    if (bytes && fread(out, 1, bytes, f) != bytes) die("workload", "file is truncated");
}

static uint32_t read_u32(FILE *f) {
    uint32_t x;
    read_exact(f, &x, sizeof x);
    return x;
}

static void *allocate(size_t bytes) {
    void *p = malloc(bytes ? bytes : 1);
    if (!p) die("out of memory", NULL);
    return p;
}

/* One input ray, as written by Rust's scratchwave_kernel::ray::Ray. */
typedef struct {
    float org[3], tnear, dir[3], tfar;
} InRay;
_Static_assert(sizeof(InRay) == 32, "Ray");

/* One answer: the fields of scratchwave_kernel::ray::Hit. geom_id = INVALID_ID is a miss. */
typedef struct {
    float ng[3], t, u, v;
    uint32_t geom_id, prim_id;
} OutHit;

typedef struct {
    uint32_t n;
    InRay *rays;
} RaySet;

/* FNV-1a over 32-bit words, each fed low byte first. The Rust side hashes identically. */
static uint64_t fnv_word(uint64_t h, uint32_t w) {
    for (int i = 0; i < 4; i++) {
        h ^= (w >> (8 * i)) & 0xffu;
        h *= 0x100000001b3ull;
    }
    return h;
}

static uint32_t bits(float x) {
    uint32_t b;
    memcpy(&b, &x, sizeof b);
    return b;
}

/* Per ray: a hit feeds geom, prim, t, u, v, ng (8 words); a miss feeds one INVALID_ID word. */
static uint64_t hash_hits(const OutHit *hits, uint32_t n, uint64_t *hit_count) {
    uint64_t h = 0xcbf29ce484222325ull, count = 0;
    for (uint32_t i = 0; i < n; i++) {
        const OutHit *o = &hits[i];
        if (o->geom_id == INVALID_ID) {
            h = fnv_word(h, INVALID_ID);
            continue;
        }
        count++;
        uint32_t words[8] = {o->geom_id, o->prim_id, bits(o->t), bits(o->u),
                             bits(o->v),  bits(o->ng[0]), bits(o->ng[1]), bits(o->ng[2])};
        for (int k = 0; k < 8; k++) h = fnv_word(h, words[k]);
    }
    *hit_count = count;
    return h;
}

/* Per ray one word: 1 occluded, 0 not. */
static uint64_t hash_occluded(const uint8_t *occluded, uint32_t n, uint64_t *hit_count) {
    uint64_t h = 0xcbf29ce484222325ull, count = 0;
    for (uint32_t i = 0; i < n; i++) {
        count += occluded[i];
        h = fnv_word(h, occluded[i]);
    }
    *hit_count = count;
    return h;
}

/* ---- the traced paths --------------------------------------------------------------------- */

static void args_init(QueryArgs *a, int flags) {
    memset(a, 0, sizeof *a);
    a->flags = flags;
    a->feature_mask = FEATURES_ALL;
}

static void trace_single(Scene scene, const RaySet *set, OutHit *out) {
    QueryArgs args;
    args_init(&args, QUERY_INCOHERENT);
    for (uint32_t i = 0; i < set->n; i++) {
        const InRay *r = &set->rays[i];
        RayHit1 rh;
        rh.ray.org_x = r->org[0];
        rh.ray.org_y = r->org[1];
        rh.ray.org_z = r->org[2];
        rh.ray.tnear = r->tnear;
        rh.ray.dir_x = r->dir[0];
        rh.ray.dir_y = r->dir[1];
        rh.ray.dir_z = r->dir[2];
        rh.ray.time = 0.0f;
        rh.ray.tfar = r->tfar;
        rh.ray.mask = 0xffffffffu;
        rh.ray.id = 0;
        rh.ray.flags = 0;
        rh.hit.geom_id = INVALID_ID;
        rh.hit.prim_id = INVALID_ID;
        rh.hit.inst_id[0] = INVALID_ID;
        rh.hit.inst_prim_id[0] = INVALID_ID;
        rtc.intersect1(scene, &rh, &args);
        OutHit *o = &out[i];
        o->geom_id = rh.hit.geom_id;
        if (rh.hit.geom_id != INVALID_ID) {
            o->ng[0] = rh.hit.ng_x;
            o->ng[1] = rh.hit.ng_y;
            o->ng[2] = rh.hit.ng_z;
            o->t = rh.ray.tfar;
            o->u = rh.hit.u;
            o->v = rh.hit.v;
            o->prim_id = rh.hit.prim_id;
        }
    }
}

/* Packets of N consecutive rays; a short last packet masks its unused lanes off. */
#define TRACE_PACKET(N)                                                                    \
    static void trace_packet##N(Scene scene, const RaySet *set, OutHit *out, int flags) {  \
        QueryArgs args;                                                                    \
        args_init(&args, flags);                                                           \
        alignas(64) int valid[N];                                                          \
        RayHit##N p;                                                                       \
        for (uint32_t first = 0; first < set->n; first += N) {                             \
            uint32_t lanes = set->n - first < N ? set->n - first : N;                      \
            for (uint32_t k = 0; k < N; k++) {                                             \
                valid[k] = k < lanes ? -1 : 0;                                             \
                const InRay *r = &set->rays[first + (k < lanes ? k : 0)];                  \
                p.ray.org_x[k] = r->org[0];                                                \
                p.ray.org_y[k] = r->org[1];                                                \
                p.ray.org_z[k] = r->org[2];                                                \
                p.ray.tnear[k] = r->tnear;                                                 \
                p.ray.dir_x[k] = r->dir[0];                                                \
                p.ray.dir_y[k] = r->dir[1];                                                \
                p.ray.dir_z[k] = r->dir[2];                                                \
                p.ray.time[k] = 0.0f;                                                      \
                p.ray.tfar[k] = r->tfar;                                                   \
                p.ray.mask[k] = 0xffffffffu;                                               \
                p.ray.id[k] = 0;                                                           \
                p.ray.flags[k] = 0;                                                        \
                p.hit.geom_id[k] = INVALID_ID;                                             \
                p.hit.prim_id[k] = INVALID_ID;                                             \
                p.hit.inst_id[0][k] = INVALID_ID;                                          \
                p.hit.inst_prim_id[0][k] = INVALID_ID;                                     \
            }                                                                              \
            rtc.intersect##N(valid, scene, &p, &args);                                     \
            for (uint32_t k = 0; k < lanes; k++) {                                         \
                OutHit *o = &out[first + k];                                               \
                o->geom_id = p.hit.geom_id[k];                                             \
                if (o->geom_id != INVALID_ID) {                                            \
                    o->ng[0] = p.hit.ng_x[k];                                              \
                    o->ng[1] = p.hit.ng_y[k];                                              \
                    o->ng[2] = p.hit.ng_z[k];                                              \
                    o->t = p.ray.tfar[k];                                                  \
                    o->u = p.hit.u[k];                                                     \
                    o->v = p.hit.v[k];                                                     \
                    o->prim_id = p.hit.prim_id[k];                                         \
                }                                                                          \
            }                                                                              \
        }                                                                                  \
    }

TRACE_PACKET(8)
TRACE_PACKET(16)

static void trace_occluded(Scene scene, const RaySet *set, uint8_t *out) {
    QueryArgs args;
    args_init(&args, QUERY_INCOHERENT);
    for (uint32_t i = 0; i < set->n; i++) {
        const InRay *r = &set->rays[i];
        Ray1 ray = {.org_x = r->org[0],
                    .org_y = r->org[1],
                    .org_z = r->org[2],
                    .tnear = r->tnear,
                    .dir_x = r->dir[0],
                    .dir_y = r->dir[1],
                    .dir_z = r->dir[2],
                    .time = 0.0f,
                    .tfar = r->tfar,
                    .mask = 0xffffffffu};
        rtc.occluded1(scene, &ray, &args);
        out[i] = ray.tfar == -INFINITY;
    }
}

/* ---- main --------------------------------------------------------------------------------- */

static void load_library(const char *path) {
    void *lib = dlopen(path, RTLD_NOW | RTLD_LOCAL);
    if (!lib) die("dlopen", dlerror());
#define LOAD(field, name) *(void **)&rtc.field = symbol(lib, name)
    LOAD(new_device, "rtcNewDevice");
    LOAD(release_device, "rtcReleaseDevice");
    LOAD(device_property, "rtcGetDeviceProperty");
    LOAD(device_error, "rtcGetDeviceError");
    LOAD(last_error_message, "rtcGetDeviceLastErrorMessage");
    LOAD(new_scene, "rtcNewScene");
    LOAD(release_scene, "rtcReleaseScene");
    LOAD(set_build_quality, "rtcSetSceneBuildQuality");
    LOAD(set_scene_flags, "rtcSetSceneFlags");
    LOAD(commit_scene, "rtcCommitScene");
    LOAD(new_geometry, "rtcNewGeometry");
    LOAD(new_buffer, "rtcSetNewGeometryBuffer");
    LOAD(commit_geometry, "rtcCommitGeometry");
    LOAD(attach, "rtcAttachGeometry");
    LOAD(release_geometry, "rtcReleaseGeometry");
    LOAD(intersect1, "rtcIntersect1");
    LOAD(intersect8, "rtcIntersect8");
    LOAD(intersect16, "rtcIntersect16");
    LOAD(occluded1, "rtcOccluded1");
#undef LOAD
}

/* Reads the mesh straight into Embree's buffers and the ray sets into `sets`. */
static Scene load_scene(Device device, FILE *f, RaySet **sets, uint32_t *set_count) {
    char magic[8];
    read_exact(f, magic, sizeof magic);
    if (memcmp(magic, "SWRAYS01", 8) != 0) die("workload", "bad magic");
    uint32_t nv = read_u32(f), nt = read_u32(f);
    *set_count = read_u32(f);

    Scene scene = rtc.new_scene(device);
    check(device, "rtcNewScene");
    rtc.set_build_quality(scene, BUILD_QUALITY_MEDIUM);
    rtc.set_scene_flags(scene, SCENE_FLAG_NONE);
    Geometry g = rtc.new_geometry(device, GEOMETRY_TRIANGLE);
    check(device, "rtcNewGeometry");
    void *vb = rtc.new_buffer(g, BUFFER_VERTEX, 0, FORMAT_FLOAT3, 12, nv);
    check(device, "vertex buffer");
    read_exact(f, vb, (size_t)nv * 12);
    void *ib = rtc.new_buffer(g, BUFFER_INDEX, 0, FORMAT_UINT3, 12, nt);
    check(device, "index buffer");
    read_exact(f, ib, (size_t)nt * 12);
    for (uint32_t i = 0; i < 3 * nt; i++)
        if (((uint32_t *)ib)[i] >= nv) die("workload", "vertex index out of range");
    rtc.commit_geometry(g);
    check(device, "rtcCommitGeometry");
    rtc.attach(scene, g);
    rtc.release_geometry(g);
    check(device, "rtcAttachGeometry");

    *sets = allocate(*set_count * sizeof(RaySet));
    for (uint32_t s = 0; s < *set_count; s++) {
        (*sets)[s].n = read_u32(f);
        (*sets)[s].rays = allocate((size_t)(*sets)[s].n * sizeof(InRay));
        read_exact(f, (*sets)[s].rays, (size_t)(*sets)[s].n * sizeof(InRay));
    }
    rtc.commit_scene(scene);
    check(device, "rtcCommitScene");
    return scene;
}

int main(int argc, char **argv) {
    if (argc != 4) die("usage", "embree_rays LIBRARY DEVICE_CONFIG WORKLOAD");
    load_library(argv[1]);
    Device device = rtc.new_device(argv[2]);
    if (!device) die("rtcNewDevice", "failed");
    FILE *f = fopen(argv[3], "rb");
    if (!f) die("cannot open", argv[3]);
    RaySet *sets;
    uint32_t set_count;
    double t0 = cpu_now();
    Scene scene = load_scene(device, f, &sets, &set_count);
    double build = cpu_now() - t0;
    fclose(f);

    uint32_t most = 0;
    for (uint32_t s = 0; s < set_count; s++) most = sets[s].n > most ? sets[s].n : most;
    OutHit *hits = allocate((size_t)most * sizeof(OutHit));
    uint8_t *occluded = allocate(most);
    double *block_best = allocate(((size_t)most + 15) / 16 * sizeof(double));

    printf("ready %ld %.6f\n", rtc.device_property(device, PROPERTY_VERSION), build);
    fflush(stdout);

    char line[256];
    while (fgets(line, sizeof line, stdin)) {
        char command[16], path[32];
        unsigned set, coherent, min_passes, block;
        double min_seconds;
        if (sscanf(line, "%15s", command) != 1 || strcmp(command, "quit") == 0) break;
        if (strcmp(command, "run") != 0 ||
            sscanf(line, "run %u %31s %u %lf %u %u", &set, path, &coherent, &min_seconds,
                   &min_passes, &block) != 6 ||
            set >= set_count || block == 0 || block % 16 != 0)
            die("bad command", line);
        int flags = coherent ? QUERY_COHERENT : QUERY_INCOHERENT;
        int kind = strcmp(path, "intersect1") == 0    ? 1
                   : strcmp(path, "intersect8") == 0  ? 8
                   : strcmp(path, "intersect16") == 0 ? 16
                   : strcmp(path, "occluded1") == 0   ? -1
                                                      : 0;
        if (!kind) die("unknown path", path);
        const RaySet *rs = &sets[set];
        uint32_t blocks = (rs->n + block - 1) / block;
        for (uint32_t b = 0; b < blocks; b++) block_best[b] = INFINITY;
        double total = 0.0;
        unsigned passes = 0;
        while (passes < min_passes || (total < min_seconds && rs->n > 0)) {
            for (uint32_t b = 0; b < blocks; b++) {
                uint32_t first = b * block;
                RaySet part = {rs->n - first < block ? rs->n - first : block, rs->rays + first};
                double start = cpu_now();
                switch (kind) {
                case 1: trace_single(scene, &part, hits + first); break;
                case 8: trace_packet8(scene, &part, hits + first, flags); break;
                case 16: trace_packet16(scene, &part, hits + first, flags); break;
                default: trace_occluded(scene, &part, occluded + first); break;
                }
                double elapsed = cpu_now() - start;
                block_best[b] = elapsed < block_best[b] ? elapsed : block_best[b];
                total += elapsed;
            }
            passes++;
        }
        double best = 0.0;
        for (uint32_t b = 0; b < blocks; b++) best += block_best[b];
        uint64_t count;
        uint64_t checksum = kind > 0 ? hash_hits(hits, rs->n, &count)
                                     : hash_occluded(occluded, rs->n, &count);
        printf("ok %u %u %.9f %.9f %llu %016llx\n", rs->n, passes, best, total,
               (unsigned long long)count, (unsigned long long)checksum);
        fflush(stdout);
    }
    rtc.release_scene(scene);
    rtc.release_device(device);
    return 0;
}
