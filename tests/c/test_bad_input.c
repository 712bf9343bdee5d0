/* The C ABI's rows of the bad-input table: each bad input and the status it must return,
 * with words its message must hold; graceful rows (inputs that are odd but valid) check the
 * documented result. Nothing may crash, leak, abort or write outside the caller's buffers:
 * run under valgrind (C11) and natively (C++17) by `make c-test`, under AddressSanitizer by
 * `make asan-test`. Prints "bad input: N rows passed, N failed". */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "tilepattern.h"

static int passed, failed;

/* One row: the call's status must be `expected` and the last error message must hold
 * `words` (NULL: any message). */
static void row(const char *what, TpStatus got, TpStatus expected, const char *words) {
  char message[512];
  tp_last_error_message(message, sizeof message);
  int ok = got == expected && (words == NULL || strstr(message, words) != NULL);
  if (ok) {
    passed++;
  } else {
    failed++;
    fprintf(stderr, "FAIL %s: status %d (expected %d), message \"%s\" (expected to contain \"%s\")\n", what, (int)got,
            (int)expected, message, words ? words : "");
  }
}

/* A check inside a graceful row. */
static void expect(const char *what, int condition) {
  if (condition) {
    passed++;
  } else {
    failed++;
    fprintf(stderr, "FAIL %s\n", what);
  }
}

/* Vertices 0-3: a unit square counter-clockwise; 4 = (2, 0), 5 = (2, 1); 6 = (2, 2),
 * 7 = (1, 2) for a second square touching the first at vertex 2. */
static const double square[] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 2, 0, 0, 2, 1, 0, 2, 2, 0, 1, 2, 0};

static TpStatus mesh(const double *v, size_t nv, const uint32_t *idx, size_t ni, const uint32_t *sizes, size_t nf,
                     TpMesh **out) {
  *out = NULL;
  TpStatus s = tp_mesh_new(v, nv, idx, ni, sizes, nf, out);
  if (s != TP_OK && *out != NULL) {
    fprintf(stderr, "FAIL: a failed tp_mesh_new wrote a handle\n");
    failed++;
  }
  return s;
}

/* Solves `m` quickly; NULL on failure (recorded as a failed row). */
static TpPattern *solve(const char *what, const TpMesh *m, TpPatternSummary *summary) {
  TpPatternOptions po;
  tp_pattern_options_init(&po, sizeof po);
  po.time_limit_seconds = 5;
  TpPattern *p = NULL;
  row(what, tp_pattern_solve(m, &po, NULL, NULL, &p), TP_OK, NULL);
  if (p != NULL) tp_pattern_summary(p, summary);
  return p;
}

/* Builds tiles of `length` on `m` and checks that every corner is finite; returns the tile
 * count, or (size_t)-1 when the build failed. */
/* Tiles laid on the mesh's faces (filler pieces the fit adds around tiles smaller than
   their quads are not counted). */
static size_t tiles_of(const char *what, const TpMesh *m, const TpPattern *p, double length) {
  TpTileOptions to;
  tp_tile_options_init(&to, sizeof to);
  to.length = length;
  to.width = length / 2;
  to.thickness = length / 20;
  to.joint = length / 20;
  TpTiles *t = NULL;
  TpStatus s = tp_tiles_build(m, p, &to, &t);
  row(what, s, TP_OK, NULL);
  if (s != TP_OK) return (size_t)-1;
  size_t n = 0, on_faces = 0;
  tp_tiles_count(t, &n);
  double corners[24 * 16];
  uint32_t faces[2 * 16];
  if (n <= 16) {
    row(what, tp_tiles_copy_corners(t, corners, sizeof corners / sizeof *corners), TP_OK, NULL);
    int finite = 1;
    for (size_t i = 0; i < 24 * n; i++) finite = finite && isfinite(corners[i]);
    expect(what, finite);
    row(what, tp_tiles_copy_faces(t, faces, sizeof faces / sizeof *faces), TP_OK, NULL);
    for (size_t i = 0; i < n; i++) on_faces += faces[2 * i] != TP_NO_FACE;
  }
  tp_tiles_free(t);
  return n <= 16 ? on_faces : n;
}

int main(void) {
  TpMesh *m = NULL;
  const uint32_t quad[] = {0, 1, 2, 3}, four[] = {4}, two_quads[] = {0, 1, 2, 3, 1, 4, 5, 2}, fours[] = {4, 4};
  const uint32_t three[] = {3, 3, 3};

  /* ---- Meshes: refused, naming the vertex, face or edge. ---- */
  double bad_v[24];
  memcpy(bad_v, square, sizeof bad_v);
  bad_v[4] = NAN;
  row("NaN coordinate", mesh(bad_v, 6, quad, 4, four, 1, &m), TP_INVALID_MESH, "vertex 1");
  bad_v[4] = INFINITY;
  row("+inf coordinate", mesh(bad_v, 6, quad, 4, four, 1, &m), TP_INVALID_MESH, "vertex 1");
  bad_v[4] = -INFINITY;
  row("-inf coordinate", mesh(bad_v, 6, quad, 4, four, 1, &m), TP_INVALID_MESH, "vertex 1");
  bad_v[4] = 0;
  bad_v[15] = 1e13;
  row("coordinate over 1e12 (unused vertex 5)", mesh(bad_v, 6, quad, 4, four, 1, &m), TP_INVALID_MESH, "vertex 5");
  const uint32_t out_of_range[] = {0, 1, 9, 3};
  row("index out of range", mesh(square, 6, out_of_range, 4, four, 1, &m), TP_INVALID_MESH, "face 0 refers to vertex 9");
  const uint32_t negative[] = {0, 1, (uint32_t)-1, 3};
  row("negative index (-1 as uint32_t)", mesh(square, 6, negative, 4, four, 1, &m), TP_INVALID_MESH, "vertex 4294967295");
  const uint32_t repeated[] = {0, 1, 1, 3};
  row("repeated vertex", mesh(square, 6, repeated, 4, four, 1, &m), TP_INVALID_MESH, "face 0 uses vertex 1 more than once");
  const uint32_t zero[] = {0}, two[] = {2};
  row("face of size 0", mesh(square, 6, quad, 0, zero, 1, &m), TP_INVALID_MESH, "face 0 has 0 vertices");
  row("face of size 2", mesh(square, 6, quad, 2, two, 1, &m), TP_INVALID_MESH, "at least 3");
  const uint32_t dup[] = {0, 1, 2, 3, 1, 2, 3, 0};
  row("duplicate face", mesh(square, 6, dup, 8, fours, 2, &m), TP_INVALID_MESH, "face 1 repeats face 0");
  const uint32_t reversed[] = {0, 1, 2, 3, 3, 2, 1, 0};
  row("duplicate face, reversed", mesh(square, 6, reversed, 8, fours, 2, &m), TP_INVALID_MESH, "face 1 repeats face 0");
  const uint32_t flipped[] = {0, 1, 2, 3, 2, 5, 4, 1};
  row("inconsistent orientation", mesh(square, 6, flipped, 8, fours, 2, &m), TP_INVALID_MESH, "faces [0, 1]");
  const uint32_t fan[] = {0, 1, 2, 1, 0, 3, 0, 1, 5};
  row("non-manifold edge", mesh(square, 6, fan, 9, three, 3, &m), TP_INVALID_MESH, "edge 0-1 is shared by 3 faces");
  /* The third face's corners on a line (vertex 4 continues the edge): a face without area. */
  const uint32_t flat_fin[] = {0, 1, 2, 1, 0, 3, 0, 1, 4};
  row("face without area on an edge", mesh(square, 6, flat_fin, 9, three, 3, &m), TP_INVALID_MESH,
      "face 2 has no area");
  row("empty mesh", mesh(NULL, 0, NULL, 0, NULL, 0, &m), TP_INVALID_MESH, "empty");
  row("vertices but no faces", mesh(square, 6, NULL, 0, NULL, 0, &m), TP_INVALID_MESH, "0 faces");
  row("faces but no vertices", mesh(NULL, 0, quad, 4, four, 1, &m), TP_INVALID_MESH, "0 vertices");

  /* ---- Meshes: counts and pointers (checked before anything is read or allocated). ---- */
  row("sizes do not add up", mesh(square, 6, quad, 3, four, 1, &m), TP_INVALID_ARGUMENT, "add up to 4, but index_count is 3");
  const uint32_t huge_size[] = {UINT32_MAX};
  row("face size UINT32_MAX", mesh(square, 6, quad, 4, huge_size, 1, &m), TP_INVALID_ARGUMENT, "add up");
  row("NULL vertices", mesh(NULL, 6, quad, 4, four, 1, &m), TP_NULL_POINTER, "vertices");
  row("NULL face_indices", mesh(square, 6, NULL, 4, four, 1, &m), TP_NULL_POINTER, "face_indices");
  row("NULL face_sizes", mesh(square, 6, quad, 4, NULL, 1, &m), TP_NULL_POINTER, "face_sizes");
  row("vertex_count SIZE_MAX", mesh(square, SIZE_MAX, quad, 4, four, 1, &m), TP_INVALID_ARGUMENT, "vertices");
  row("vertex_count SIZE_MAX / 3 + 1", mesh(square, SIZE_MAX / 3 + 1, quad, 4, four, 1, &m), TP_INVALID_ARGUMENT,
      "at most 4000000");
  row("vertex_count 4000001", mesh(square, 4000001, quad, 4, four, 1, &m), TP_INVALID_ARGUMENT, "4000001 vertices");
  row("index_count SIZE_MAX", mesh(square, 6, quad, SIZE_MAX, four, 1, &m), TP_INVALID_ARGUMENT, "face indices");
  row("face_count SIZE_MAX", mesh(square, 6, quad, 4, four, SIZE_MAX, &m), TP_INVALID_ARGUMENT, "faces");
  row("face_count 2^40", mesh(square, 6, quad, 4, four, (size_t)1 << 40, &m), TP_INVALID_ARGUMENT, "faces");
  row("NULL out", tp_mesh_new(square, 6, quad, 4, four, 1, NULL), TP_NULL_POINTER, "out");

  /* ---- Meshes: graceful rows. ---- */
  TpPatternSummary sum;
  {
    /* A zero-area face (face 1: corners 1, 2 and 5 at one point): accepted, finite tiles. */
    double flat[18];
    memcpy(flat, square, sizeof flat);
    flat[6] = flat[15] = 1, flat[7] = flat[16] = 0;
    row("zero-area face (graceful: accepted)", mesh(flat, 6, two_quads, 8, fours, 2, &m), TP_OK, NULL);
    TpPattern *p = solve("zero-area face: solve", m, &sum);
    if (p) expect("zero-area face: tiles", tiles_of("zero-area face: tiles", m, p, 0.5) != (size_t)-1);
    tp_pattern_free(p);
    tp_mesh_free(m);
  }
  {
    /* Two quads touching at vertex 2 only: accepted, two half tiles. */
    const uint32_t bowtie[] = {0, 1, 2, 3, 2, 5, 6, 7};
    row("non-manifold vertex (graceful: accepted)", mesh(square, 8, bowtie, 8, fours, 2, &m), TP_OK, NULL);
    TpPattern *p = solve("non-manifold vertex: solve", m, &sum);
    expect("non-manifold vertex: 0 pairs, 2 unpaired", p && sum.pairs == 0 && sum.unpaired == 2);
    if (p) expect("non-manifold vertex: 2 tiles", tiles_of("non-manifold vertex: tiles", m, p, 1.0) == 2);
    /* Faces 0 and 1 share no edge: forcing them into one tile is refused. */
    TpPatternOptions po;
    tp_pattern_options_init(&po, sizeof po);
    const uint32_t apart[] = {0, 1};
    po.forced_pairs = apart;
    po.forced_pair_count = 1;
    TpPattern *q = NULL;
    row("forced pair not adjacent", tp_pattern_solve(m, &po, NULL, NULL, &q), TP_INVALID_ARGUMENT, "do not share an edge");
    tp_pattern_free(p);
    tp_mesh_free(m);
  }
  {
    /* Two separate pieces of two quads each: each matched on its own. */
    double v[36];
    memcpy(v, square, 18 * sizeof(double));
    for (int i = 0; i < 18; i++) v[18 + i] = square[i] + (i % 3 == 0 ? 10.0 : 0.0);
    const uint32_t pieces[] = {0, 1, 2, 3, 1, 4, 5, 2, 6, 7, 8, 9, 7, 10, 11, 8}, sizes[] = {4, 4, 4, 4};
    row("disconnected pieces (graceful: accepted)", mesh(v, 12, pieces, 16, sizes, 4, &m), TP_OK, NULL);
    TpPattern *p = solve("disconnected pieces: solve", m, &sum);
    expect("disconnected pieces: 2 pairs", p && sum.pairs == 2 && sum.unpaired == 0);
    if (p) expect("disconnected pieces: 2 tiles", tiles_of("disconnected pieces: tiles", m, p, 1.9) == 2);
    tp_pattern_free(p);
    tp_mesh_free(m);
  }
  {
    row("single quad (graceful: one half tile)", mesh(square, 6, quad, 4, four, 1, &m), TP_OK, NULL);
    TpPattern *p = solve("single quad: solve", m, &sum);
    expect("single quad: 1 unpaired", p && sum.pairs == 0 && sum.unpaired == 1);
    if (p) expect("single quad: 1 tile", tiles_of("single quad: tiles", m, p, 1.0) == 1);
    tp_pattern_free(p);
    tp_mesh_free(m);
  }
  {
    /* Triangles only: nothing to pair, every face reported as not a quad, no tile. */
    const uint32_t tris[] = {0, 1, 2, 0, 2, 3}, threes[] = {3, 3};
    row("only triangles (graceful: accepted)", mesh(square, 4, tris, 6, threes, 2, &m), TP_OK, NULL);
    TpPattern *p = solve("only triangles: solve", m, &sum);
    expect("only triangles: 0 pairs, 2 non-quad", p && sum.pairs == 0 && sum.unpaired == 0 && sum.non_quad == 2);
    if (p) expect("only triangles: 0 tiles", tiles_of("only triangles: tiles", m, p, 1.0) == 0);
    TpPatternOptions po;
    tp_pattern_options_init(&po, sizeof po);
    const uint32_t pair[] = {0, 1};
    po.forced_pairs = pair;
    po.forced_pair_count = 1;
    TpPattern *q = NULL;
    row("forced pair of triangles", tp_pattern_solve(m, &po, NULL, NULL, &q), TP_INVALID_ARGUMENT, "face 0 has 3 corners");
    tp_pattern_free(p);
    tp_mesh_free(m);
  }

  /* ---- Pattern options, on a valid 2-quad mesh. ---- */
  TpMesh *quads = NULL;
  row("valid mesh", mesh(square, 6, two_quads, 8, fours, 2, &quads), TP_OK, NULL);
  TpPattern *p = NULL;
  TpPatternOptions po;
  const double bad_weights[] = {NAN, -1, INFINITY, -INFINITY, 1000.5, 1e30, 1e300};
  for (size_t i = 0; i < sizeof bad_weights / sizeof *bad_weights; i++) {
    for (int bond = TP_BOND_STAGGERED; bond <= TP_BOND_RUNNING; bond++) {
      tp_pattern_options_init(&po, sizeof po);
      po.bond = bond;
      po.weight = bad_weights[i];
      char what[64];
      snprintf(what, sizeof what, "weight %g, bond %d", bad_weights[i], bond);
      row(what, tp_pattern_solve(quads, &po, NULL, NULL, &p), TP_INVALID_ARGUMENT, "weight");
    }
  }
  tp_pattern_options_init(&po, sizeof po);
  po.time_limit_seconds = -1;
  row("negative time limit", tp_pattern_solve(quads, &po, NULL, NULL, &p), TP_INVALID_ARGUMENT, "time limit -1");
  po.time_limit_seconds = NAN;
  row("NaN time limit", tp_pattern_solve(quads, &po, NULL, NULL, &p), TP_INVALID_ARGUMENT, "time limit NaN");
  po.time_limit_seconds = INFINITY;
  row("infinite time limit", tp_pattern_solve(quads, &po, NULL, NULL, &p), TP_INVALID_ARGUMENT, "time limit inf");
  po.time_limit_seconds = 1e19;
  row("time limit 1e19 s (graceful: counts as 1e9 s)", tp_pattern_solve(quads, &po, NULL, NULL, &p), TP_OK, NULL);
  tp_pattern_free(p);
  p = NULL;
  tp_pattern_options_init(&po, sizeof po);
  po.bond = 99;
  row("unknown bond", tp_pattern_solve(quads, &po, NULL, NULL, &p), TP_INVALID_ARGUMENT, "bond 99");
  tp_pattern_options_init(&po, sizeof po);
  po.method = -1;
  row("unknown method", tp_pattern_solve(quads, &po, NULL, NULL, &p), TP_INVALID_ARGUMENT, "method -1");
  tp_pattern_options_init(&po, sizeof po);
  po.formulation = 7;
  row("unknown formulation", tp_pattern_solve(quads, &po, NULL, NULL, &p), TP_INVALID_ARGUMENT, "formulation 7");
  tp_pattern_options_init(&po, sizeof po);
  const uint32_t far_pair[] = {0, 7};
  po.forced_pairs = far_pair;
  po.forced_pair_count = 1;
  row("forced pair out of range", tp_pattern_solve(quads, &po, NULL, NULL, &p), TP_INVALID_ARGUMENT, "face 7");
  po.forced_pairs = NULL;
  row("NULL forced pairs", tp_pattern_solve(quads, &po, NULL, NULL, &p), TP_NULL_POINTER, "forced");
  po.forced_pairs = far_pair;
  po.forced_pair_count = SIZE_MAX;
  row("forced_pair_count SIZE_MAX", tp_pattern_solve(quads, &po, NULL, NULL, &p), TP_INVALID_ARGUMENT, "forced_pair_count");
  po.forced_pair_count = SIZE_MAX / 2 + 1;
  row("forced_pair_count overflowing x2", tp_pattern_solve(quads, &po, NULL, NULL, &p), TP_INVALID_ARGUMENT, "forced_pair_count");
  tp_pattern_options_init(&po, sizeof po);
  const uint32_t excluded[] = {9};
  po.excluded_faces = excluded;
  po.excluded_face_count = 1;
  row("excluded face out of range", tp_pattern_solve(quads, &po, NULL, NULL, &p), TP_INVALID_ARGUMENT, "face 9");
  po.excluded_face_count = SIZE_MAX;
  row("excluded_face_count SIZE_MAX", tp_pattern_solve(quads, &po, NULL, NULL, &p), TP_INVALID_ARGUMENT, "excluded_face_count");
  tp_pattern_options_init(&po, sizeof po);
  po.struct_size = 2;
  row("struct_size too small", tp_pattern_solve(quads, &po, NULL, NULL, &p), TP_INVALID_ARGUMENT, "struct_size");
  po.struct_size = 1u << 20;
  row("struct_size absurd", tp_pattern_solve(quads, &po, NULL, NULL, &p), TP_INVALID_ARGUMENT, "struct_size");
  row("NULL options", tp_pattern_solve(quads, NULL, NULL, NULL, &p), TP_NULL_POINTER, "options");
  /* The relative gap (ABI 4). */
  const double bad_gaps[] = {-0.01, 1.5, NAN, INFINITY};
  for (size_t i = 0; i < sizeof bad_gaps / sizeof *bad_gaps; i++) {
    tp_pattern_options_init(&po, sizeof po);
    po.gap = bad_gaps[i];
    char what[64];
    snprintf(what, sizeof what, "gap %g", bad_gaps[i]);
    row(what, tp_pattern_solve(quads, &po, NULL, NULL, &p), TP_INVALID_ARGUMENT, "relative gap");
  }
  /* Courses (ABI 3). */
  const int32_t bad_courses[] = {7, -1, 2};
  for (size_t i = 0; i < sizeof bad_courses / sizeof *bad_courses; i++) {
    tp_pattern_options_init(&po, sizeof po);
    po.courses = bad_courses[i];
    char what[64], words[32];
    snprintf(what, sizeof what, "unknown courses %d", (int)bad_courses[i]);
    snprintf(words, sizeof words, "courses %d", (int)bad_courses[i]);
    row(what, tp_pattern_solve(quads, &po, NULL, NULL, &p), TP_INVALID_ARGUMENT, words);
  }
  const double bad_ups[][3] = {{0, 0, 0}, {NAN, 0, 1}, {0, INFINITY, 0}};
  for (size_t i = 0; i < sizeof bad_ups / sizeof *bad_ups; i++) {
    tp_pattern_options_init(&po, sizeof po);
    po.courses = TP_COURSES_LEVEL;
    memcpy(po.up, bad_ups[i], sizeof po.up);
    char what[64];
    snprintf(what, sizeof what, "level courses, up (%g, %g, %g)", bad_ups[i][0], bad_ups[i][1], bad_ups[i][2]);
    row(what, tp_pattern_solve(quads, &po, NULL, NULL, &p), TP_INVALID_ARGUMENT, "up direction");
  }
  tp_pattern_options_init(&po, sizeof po);
  po.up[0] = po.up[1] = po.up[2] = 0;
  row("free courses, up (0, 0, 0) (graceful: up is only read for level courses)", tp_pattern_solve(quads, &po, NULL, NULL, &p),
      TP_OK, NULL);
  tp_pattern_free(p);
  p = NULL;
  {
    /* Up along x: courses run along y, so faces 0 and 1 (side by side along x) lie in two. */
    tp_pattern_options_init(&po, sizeof po);
    po.courses = TP_COURSES_LEVEL;
    po.up[0] = 1, po.up[1] = 0, po.up[2] = 0;
    const uint32_t across[] = {0, 1};
    po.forced_pairs = across;
    po.forced_pair_count = 1;
    row("forced pair across level courses", tp_pattern_solve(quads, &po, NULL, NULL, &p), TP_INVALID_ARGUMENT, "two courses");
  }
  {
    /* Zones, a bond per face (ABI 6): the mesh has 2 faces. */
    const int32_t one_zone[] = {TP_BOND_STACK}, bad_code[] = {TP_ZONE_DEFAULT, 9},
                  herringbone[] = {TP_BOND_HERRINGBONE, TP_ZONE_DEFAULT};
    tp_pattern_options_init(&po, sizeof po);
    po.zones = one_zone;
    po.zone_count = 1;
    row("zones for 1 face of 2", tp_pattern_solve(quads, &po, NULL, NULL, &p), TP_INVALID_ARGUMENT,
        "1 bonds for a mesh of 2 faces");
    po.zones = bad_code;
    po.zone_count = 2;
    row("unknown zone code", tp_pattern_solve(quads, &po, NULL, NULL, &p), TP_INVALID_ARGUMENT, "options->zones[1] is 9");
    po.zones = NULL;
    row("NULL zones, zone_count 2", tp_pattern_solve(quads, &po, NULL, NULL, &p), TP_NULL_POINTER, "zones");
    po.zones = one_zone;
    po.zone_count = SIZE_MAX;
    row("zone_count SIZE_MAX", tp_pattern_solve(quads, &po, NULL, NULL, &p), TP_INVALID_ARGUMENT, "zone_count");
    po.zones = herringbone;
    po.zone_count = 2;
    po.courses = TP_COURSES_LEVEL;
    row("herringbone zone in level courses", tp_pattern_solve(quads, &po, NULL, NULL, &p), TP_INVALID_ARGUMENT,
        "courses free");
    po.bond = TP_BOND_STACK;
    po.weight = NAN;
    po.courses = TP_COURSES_FREE;
    row("zone weight NaN (stack ignores it, a herringbone zone does not)", tp_pattern_solve(quads, &po, NULL, NULL, &p),
        TP_INVALID_ARGUMENT, "zone of face 0");
    po.zones = NULL;
    po.zone_count = 0;
    row("zone weight NaN without zones (graceful: stack has no weight)", tp_pattern_solve(quads, &po, NULL, NULL, &p),
        TP_OK, NULL);
    tp_pattern_free(p);
    p = NULL;
  }
  tp_pattern_options_init(&po, sizeof po);
  row("NULL mesh", tp_pattern_solve(NULL, &po, NULL, NULL, &p), TP_NULL_POINTER, "mesh");
  row("options_init size 0", tp_pattern_options_init(&po, 0), TP_INVALID_ARGUMENT, "size 0");
  tp_pattern_options_init(&po, sizeof po);
  po.time_limit_seconds = 0;
  row("time limit 0 (graceful: the best start)", tp_pattern_solve(quads, &po, NULL, NULL, &p), TP_OK, NULL);
  expect("pattern handle written", p != NULL);

  /* ---- Tile options. ---- */
  TpTiles *t = NULL;
  TpTileOptions to;
  struct {
    const char *what;
    int field;
    double value;
    const char *words;
  } tile_rows[] = {
      {"zero tile length", 0, 0, "length 0"},       {"negative tile length", 0, -0.3, "length -0.3"},
      {"NaN tile length", 0, NAN, "length NaN"},    {"NaN tile width", 1, NAN, "width NaN"},
      {"infinite thickness", 2, INFINITY, "thickness inf"}, {"negative joint", 3, -0.01, "joint -0.01"},
      {"NaN cut tolerance", 4, NAN, "tolerance NaN"}, {"infinite min kept width", 5, INFINITY, "min_kept_width"},
      {"NaN support band", 6, NAN, "support_band"},
  };
  for (size_t i = 0; i < sizeof tile_rows / sizeof *tile_rows; i++) {
    tp_tile_options_init(&to, sizeof to);
    to.length = 1.9, to.width = 0.95;
    double *fields[] = {&to.length, &to.width, &to.thickness, &to.joint, &to.cut_tolerance, &to.min_kept_width, &to.support_band};
    *fields[tile_rows[i].field] = tile_rows[i].value;
    row(tile_rows[i].what, tp_tiles_build(quads, p, &to, &t), TP_INVALID_ARGUMENT, tile_rows[i].words);
  }
  /* The fit stage's options (ABI 3). */
  struct {
    const char *what;
    int field;
    double value;
    const char *words;
  } fit_rows[] = {
      {"NaN fit time limit", 0, NAN, "fit_time_limit_seconds NaN"},
      {"negative fit time limit", 0, -1, "fit_time_limit_seconds -1"},
      {"infinite fit time limit", 0, INFINITY, "fit_time_limit_seconds inf"},
      {"NaN fit overlap tolerance", 1, NAN, "overlap_tolerance NaN"},
      {"infinite fit overlap tolerance", 1, INFINITY, "overlap_tolerance inf"},
      {"NaN fit bond tolerance", 2, NAN, "bond_tolerance NaN"},
      {"zero units per mm", 3, 0, " 0 must be"},
      {"negative units per mm", 3, -1, "-1 must be"},
      {"NaN units per mm", 3, NAN, "NaN must be"},
  };
  for (size_t i = 0; i < sizeof fit_rows / sizeof *fit_rows; i++) {
    tp_tile_options_init(&to, sizeof to);
    to.length = 1.9, to.width = 0.95;
    double *fields[] = {&to.fit_time_limit_seconds, &to.fit_overlap_tolerance, &to.fit_bond_tolerance, &to.units_per_mm};
    *fields[fit_rows[i].field] = fit_rows[i].value;
    row(fit_rows[i].what, tp_tiles_build(quads, p, &to, &t), TP_INVALID_ARGUMENT, fit_rows[i].words);
  }
  tp_tile_options_init(&to, sizeof to);
  to.length = 1.9, to.width = 0.95;
  to.fit = 0;
  to.fit_time_limit_seconds = NAN;
  row("NaN fit time limit with the fit off (graceful: not read)", tp_tiles_build(quads, p, &to, &t), TP_OK, NULL);
  tp_tiles_free(t);
  t = NULL;
  tp_tile_options_init(&to, sizeof to);
  to.length = 1.9, to.width = 0.95;
  to.fit = 7;
  row("fit 7 (graceful: any non-zero value is on)", tp_tiles_build(quads, p, &to, &t), TP_OK, NULL);
  tp_tiles_free(t);
  t = NULL;
  tp_tile_options_init(&to, sizeof to);
  to.length = 1.9, to.width = 0.95;
  row("NULL tiles out with progress", tp_tiles_build_with_progress(quads, p, NULL, &to, NULL, NULL, NULL), TP_NULL_POINTER, "out");
  to.fit_time_limit_seconds = -1;
  row("negative fit time limit with progress", tp_tiles_build_with_progress(quads, p, NULL, &to, NULL, NULL, &t),
      TP_INVALID_ARGUMENT, "time_limit");
  tp_tile_options_init(&to, sizeof to);
  to.length = 100;
  row("tile larger than the shell", tp_tiles_build(quads, p, &to, &t), TP_INVALID_ARGUMENT, "larger than the whole mesh");
  to.length = 2e-6, to.width = 1e-6, to.thickness = 1e-7, to.joint = 0;
  row("tile a million times smaller than the faces", tp_tiles_build(quads, p, &to, &t), TP_INVALID_ARGUMENT, "same units");
  tp_tile_options_init(&to, sizeof to);
  to.up[0] = to.up[1] = to.up[2] = 0;
  row("zero up direction", tp_tiles_build(quads, p, &to, &t), TP_INVALID_ARGUMENT, "up");
  tp_tile_options_init(&to, sizeof to);
  to.struct_size = 0;
  row("tile struct_size 0", tp_tiles_build(quads, p, &to, &t), TP_INVALID_ARGUMENT, "struct_size");
  TpMesh *other = NULL;
  row("valid single quad", mesh(square, 6, quad, 4, four, 1, &other), TP_OK, NULL);
  tp_tile_options_init(&to, sizeof to);
  to.length = 1.9, to.width = 0.95;
  row("pattern of another mesh", tp_tiles_build(other, p, &to, &t), TP_INVALID_PATTERN, "mesh of 2 faces");
  row("NULL pattern", tp_tiles_build(quads, NULL, &to, &t), TP_NULL_POINTER, "pattern");
  row("NULL tiles out", tp_tiles_build(quads, p, &to, NULL), TP_NULL_POINTER, "out");
  expect("no tiles handle after failures", t == NULL);

  /* ---- Buffers. ---- */
  row("valid tiles", tp_tiles_build(quads, p, &to, &t), TP_OK, NULL);
  size_t n = 0;
  tp_tiles_count(t, &n);
  double corners[48];
  row("corners buffer too small", tp_tiles_copy_corners(t, corners, 24 * n - 1), TP_BUFFER_TOO_SMALL, "are needed");
  row("corners NULL with a capacity", tp_tiles_copy_corners(t, NULL, SIZE_MAX), TP_NULL_POINTER, "out");
  row("corners capacity SIZE_MAX (graceful: writes only what there is)", tp_tiles_copy_corners(t, corners, SIZE_MAX),
      TP_OK, NULL);
  char small[4];
  size_t needed = 0;
  row("report buffer too small", tp_tiles_report_json(t, small, sizeof small, &needed), TP_BUFFER_TOO_SMALL, NULL);
  expect("report size told", needed > sizeof small);
  expect("error message length told", tp_last_error_message(NULL, 0) > 0);
  char one[1] = {'x'};
  tp_last_error_message(one, 1);
  expect("error message in a 1-byte buffer is empty", one[0] == '\0');
  double deviations[2];
  expect("two quads, one tile (and no more than two filler pieces)", n >= 1 && n <= 3);
  row("joint deviations buffer too small", tp_tiles_copy_joint_deviations(t, deviations, n - 1), TP_BUFFER_TOO_SMALL, "are needed");
  row("joint deviations NULL", tp_tiles_copy_joint_deviations(t, NULL, n), TP_NULL_POINTER, "out");
  row("joint deviations of NULL tiles", tp_tiles_copy_joint_deviations(NULL, deviations, 2), TP_NULL_POINTER, "tiles");
  uint32_t pairs[1];
  row("pairs buffer too small", tp_pattern_copy_pairs(p, pairs, 1), TP_BUFFER_TOO_SMALL, "holds 1 items, 2 are needed");
  tp_tiles_free(t);

  /* ---- Remesh options. ---- */
  TpMesh *r = NULL;
  TpRemeshOptions ro;
  const double bad_edges[] = {0, -1, NAN, INFINITY};
  for (size_t i = 0; i < sizeof bad_edges / sizeof *bad_edges; i++) {
    tp_remesh_options_init(&ro, sizeof ro);
    ro.target_edge = bad_edges[i];
    char what[64];
    snprintf(what, sizeof what, "target edge %g", bad_edges[i]);
    row(what, tp_remesh(quads, &ro, NULL, NULL, &r), TP_INVALID_ARGUMENT, "target edge");
  }
  tp_remesh_options_init(&ro, sizeof ro);
  ro.target_edge = 1e300;
  row("target edge 1e300", tp_remesh(quads, &ro, NULL, NULL, &r), TP_INVALID_ARGUMENT, "too large");
  ro.target_edge = 1e-9;
  row("target edge 1e-9", tp_remesh(quads, &ro, NULL, NULL, &r), TP_INVALID_ARGUMENT, "larger edge");
  tp_remesh_options_init(&ro, sizeof ro);
  ro.direction = TP_DIRECTION_VECTOR;
  ro.direction_vector[0] = ro.direction_vector[1] = ro.direction_vector[2] = 0;
  row("zero direction vector", tp_remesh(quads, &ro, NULL, NULL, &r), TP_INVALID_ARGUMENT, "direction");
  ro.direction = 99;
  row("unknown direction", tp_remesh(quads, &ro, NULL, NULL, &r), TP_INVALID_ARGUMENT, "direction 99");
  tp_remesh_options_init(&ro, sizeof ro);
  ro.direction = TP_DIRECTION_ANGLE;
  ro.angle_degrees = NAN;
  row("NaN angle", tp_remesh(quads, &ro, NULL, NULL, &r), TP_INVALID_ARGUMENT, "angle");
  tp_remesh_options_init(&ro, sizeof ro);
  ro.time_limit_seconds = NAN;
  row("NaN remesh time limit", tp_remesh(quads, &ro, NULL, NULL, &r), TP_INVALID_ARGUMENT, "time limit");
  ro.time_limit_seconds = 0;
  ro.target_edge = 0.1;
  row("remesh time limit 0", tp_remesh(quads, &ro, NULL, NULL, &r), TP_TIME_LIMIT, "time limit");
  {
    const double line[] = {0, 0, 0, 1, 0, 0, 2, 0, 0};
    const uint32_t tri[] = {0, 1, 2}, three1[] = {3};
    TpMesh *flat = NULL;
    row("zero-area triangle (graceful: a valid mesh)", mesh(line, 3, tri, 3, three1, 1, &flat), TP_OK, NULL);
    tp_remesh_options_init(&ro, sizeof ro);
    row("remesh of a zero-area surface", tp_remesh(flat, &ro, NULL, NULL, &r), TP_INVALID_MESH, "no area");
    tp_mesh_free(flat);
  }
  expect("no remesh handle after failures", r == NULL);

  {
    /* tp_run: every stage's options checked before anything runs; nothing handed out. */
    TpRemeshOptions rro;
    TpPatternOptions rpo;
    TpTileOptions rto;
    TpRunOptions run;
    tp_remesh_options_init(&rro, sizeof rro);
    tp_pattern_options_init(&rpo, sizeof rpo);
    tp_tile_options_init(&rto, sizeof rto);
    row("run options init", tp_run_options_init(&run, sizeof run), TP_OK, NULL);
    expect("run tries default 0 (automatic)", run.tries == 0);
    TpTiles *rt = NULL;
    TpMesh *rq = NULL;
    run.tries = 99;
    row("run: 99 tries", tp_run(quads, &rro, &rpo, &rto, &run, NULL, NULL, &rq, NULL, &rt), TP_INVALID_ARGUMENT,
        "run->tries is 99");
    run.tries = 1;
    uint32_t pair[2] = {0, 1};
    rpo.forced_pairs = pair;
    rpo.forced_pair_count = 1;
    row("run: forced pairs", tp_run(quads, &rro, &rpo, &rto, &run, NULL, NULL, &rq, NULL, &rt), TP_INVALID_ARGUMENT,
        "forced_pair_count is 1");
    rpo.forced_pairs = NULL;
    rpo.forced_pair_count = 0;
    rro.target_edge = NAN;
    row("run: NaN target edge", tp_run(quads, &rro, &rpo, &rto, &run, NULL, NULL, &rq, NULL, &rt), TP_INVALID_ARGUMENT,
        "target edge");
    rro.target_edge = 0.145;
    rto.length = -1.0;
    row("run: negative tile length", tp_run(quads, &rro, &rpo, &rto, &run, NULL, NULL, &rq, NULL, &rt),
        TP_INVALID_ARGUMENT, "length");
    rto.length = 0.28;
    rpo.bond = 99;
    row("run: unknown bond", tp_run(quads, &rro, &rpo, &rto, &run, NULL, NULL, &rq, NULL, &rt), TP_INVALID_ARGUMENT,
        "bond 99");
    rpo.bond = TP_BOND_STAGGERED;
    run.struct_size = 0;
    row("run: struct_size 0", tp_run(quads, &rro, &rpo, &rto, &run, NULL, NULL, &rq, NULL, &rt), TP_INVALID_ARGUMENT,
        "struct_size");
    run.struct_size = sizeof run;
    row("run: NULL surface", tp_run(NULL, &rro, &rpo, &rto, &run, NULL, NULL, &rq, NULL, &rt), TP_NULL_POINTER,
        "surface");
    row("run: NULL out_tiles", tp_run(quads, &rro, &rpo, &rto, &run, NULL, NULL, &rq, NULL, NULL), TP_NULL_POINTER,
        "out_tiles");
    row("run: NULL tile options", tp_run(quads, &rro, &rpo, NULL, &run, NULL, NULL, &rq, NULL, &rt), TP_NULL_POINTER,
        "tiles");
    expect("no run handles after failures", rt == NULL && rq == NULL);
  }

  {
    /* A closed cube of side 2, each side 2 x 2 unit quads (graceful: tiled, with warnings a
       caller can read: closed surface, no support). */
    double cube[3 * 26];
    uint32_t idx[4 * 24], sizes[24];
    size_t nv = 0, nf = 0;
    for (int k = 0; k < 3; k++) {
      for (int sign = -1; sign <= 1; sign += 2) {
        int a = (k + 1) % 3, b = (k + 2) % 3;
        if (sign < 0) { int t = a; a = b; b = t; } /* a x b points out of the cube */
        uint32_t at[3][3];
        for (int j = 0; j <= 2; j++) {
          for (int i = 0; i <= 2; i++) {
            double p[3];
            p[k] = sign;
            p[a] = i - 1.0;
            p[b] = j - 1.0;
            size_t found = nv;
            for (size_t v = 0; v < nv; v++)
              if (cube[3 * v] == p[0] && cube[3 * v + 1] == p[1] && cube[3 * v + 2] == p[2]) found = v;
            if (found == nv) {
              memcpy(&cube[3 * nv], p, sizeof p);
              nv++;
            }
            at[i][j] = (uint32_t)found;
          }
        }
        for (int j = 0; j < 2; j++) {
          for (int i = 0; i < 2; i++) {
            uint32_t *q = &idx[4 * nf];
            q[0] = at[i][j], q[1] = at[i + 1][j], q[2] = at[i + 1][j + 1], q[3] = at[i][j + 1];
            sizes[nf++] = 4;
          }
        }
      }
    }
    TpMesh *closed = NULL;
    row("closed cube (graceful: a valid mesh)", mesh(cube, nv, idx, 4 * nf, sizes, nf, &closed), TP_OK, NULL);
    expect("the cube has 26 vertices", nv == 26);
    TpPatternSummary cs;
    TpPattern *cp = closed ? solve("pattern of a closed cube", closed, &cs) : NULL;
    TpTileOptions to;
    tp_tile_options_init(&to, sizeof to);
    to.length = 1.9, to.width = 0.95, to.thickness = 0.1, to.joint = 0.1;
    TpTiles *ct = NULL;
    if (cp) row("tiles on a closed cube", tp_tiles_build(closed, cp, &to, &ct), TP_OK, NULL);
    if (ct) {
      size_t count = 0, needed = 0;
      row("warning count", tp_tiles_warning_count(ct, &count), TP_OK, NULL);
      expect("a closed cube gets warnings", count >= 2 && count < 16);
      TpWarning codes[16];
      row("warning codes into a short buffer", tp_tiles_copy_warning_codes(ct, codes, 1), TP_BUFFER_TOO_SMALL,
          "needed");
      row("warning codes", tp_tiles_copy_warning_codes(ct, codes, 16), TP_OK, NULL);
      int closed_seen = 0, support_seen = 0;
      for (size_t i = 0; i < count && i < 16; i++) {
        closed_seen |= codes[i] == TP_WARNING_CLOSED_SURFACE;
        support_seen |= codes[i] == TP_WARNING_NO_SUPPORT;
      }
      expect("closed surface and no support among the codes", closed_seen && support_seen);
      row("warning messages: size", tp_tiles_warnings(ct, NULL, 0, &needed), TP_BUFFER_TOO_SMALL, NULL);
      char text[4096];
      row("warning messages", tp_tiles_warnings(ct, text, sizeof text, &needed), TP_OK, NULL);
      size_t lines = 0;
      for (char *c = text; *c; c++) lines += *c == '\n';
      expect("one message a warning, naming the closed surface", lines == count && strstr(text, "closed") != NULL);
      size_t none = 99;
      row("warning count of NULL tiles", tp_tiles_warning_count(NULL, &none), TP_NULL_POINTER, "tiles");
    }
    tp_tiles_free(ct);
    tp_pattern_free(cp);
    tp_mesh_free(closed);
  }

  tp_pattern_free(p);
  tp_mesh_free(quads);
  tp_mesh_free(other);
  printf("bad input: %d rows passed, %d failed\n", passed, failed);
  return failed ? 1 : 0;
}
