/* C tests of the TilePattern ABI: every export, every error path. Compiled as C11 and as
 * C++17 with warnings as errors, run under valgrind memcheck. Prints "N passed, N failed". */
#define _POSIX_C_SOURCE 199309L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <stddef.h>
#include <string.h>
#include <time.h>

#include "tilepattern.h"

static int passed, failed;

#define CHECK(cond)                                                                     \
  do {                                                                                  \
    if (cond) {                                                                         \
      passed++;                                                                         \
    } else {                                                                            \
      failed++;                                                                         \
      char why_[512];                                                                   \
      tp_last_error_message(why_, sizeof why_);                                         \
      fprintf(stderr, "FAIL %s:%d: %s (last error: %s)\n", __FILE__, __LINE__, #cond, why_); \
    }                                                                                   \
  } while (0)

static int last_error_contains(const char *needle) {
  char buf[512];
  tp_last_error_message(buf, sizeof buf);
  return strstr(buf, needle) != NULL;
}

static double now_seconds(void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* An nx x ny grid of unit squares; caller frees the three arrays. */
static void grid(uint32_t nx, uint32_t ny, double **vertices, size_t *vertex_count, uint32_t **indices,
                 uint32_t **sizes, size_t *face_count) {
  *vertex_count = (size_t)(nx + 1) * (ny + 1);
  *face_count = (size_t)nx * ny;
  *vertices = (double *)malloc(*vertex_count * 3 * sizeof(double));
  *indices = (uint32_t *)malloc(*face_count * 4 * sizeof(uint32_t));
  *sizes = (uint32_t *)malloc(*face_count * sizeof(uint32_t));
  for (uint32_t j = 0; j <= ny; j++)
    for (uint32_t i = 0; i <= nx; i++) {
      double *v = *vertices + 3 * (i + (nx + 1) * j);
      v[0] = i;
      v[1] = j;
      v[2] = 0.0;
    }
  for (uint32_t j = 0; j < ny; j++)
    for (uint32_t i = 0; i < nx; i++) {
      uint32_t f = i + nx * j, *q = *indices + 4 * f;
      q[0] = i + (nx + 1) * j;
      q[1] = q[0] + 1;
      q[2] = q[1] + nx + 1;
      q[3] = q[0] + nx + 1;
      (*sizes)[f] = 4;
    }
}

/* A mesh made from arrays the caller allocated with malloc, which it hands over (freed here);
 * NULL when tp_mesh_new refuses them. */
static TpMesh *mesh_taking(double *v, size_t nv, uint32_t *idx, size_t ni, uint32_t *sz, size_t nf) {
  TpMesh *mesh = NULL;
  TpStatus s = tp_mesh_new(v, nv, idx, ni, sz, nf, &mesh);
  free(v);
  free(idx);
  free(sz);
  return s == TP_OK ? mesh : NULL;
}

static TpMesh *grid_mesh(uint32_t nx, uint32_t ny) {
  double *v;
  uint32_t *idx, *sz;
  size_t nv, nf;
  grid(nx, ny, &v, &nv, &idx, &sz, &nf);
  return mesh_taking(v, nv, idx, 4 * nf, sz, nf);
}

/* An nx x ny grid of unit squares lifted to z = rise * y (rise > 0: level lines along x) or,
 * with `bump`, to a doubly curved cap. */
static TpMesh *lifted_grid_mesh(uint32_t nx, uint32_t ny, double rise, int bump) {
  double *v;
  uint32_t *idx, *sz;
  size_t nv, nf;
  grid(nx, ny, &v, &nv, &idx, &sz, &nf);
  for (size_t k = 0; k < nv; k++) {
    double x = v[3 * k], y = v[3 * k + 1];
    v[3 * k + 2] = bump ? 0.8 * sin(x / 3.0) * sin(y / 2.5) : rise * y;
  }
  return mesh_taking(v, nv, idx, 4 * nf, sz, nf);
}

static void test_version(void) {
  CHECK(tp_abi_version() == TP_ABI_VERSION);
  CHECK(strlen(tp_version()) > 0);
  CHECK(tp_last_error_message(NULL, 0) == 0 || 1);
}

static void test_mesh(void) {
  double *v;
  uint32_t *idx, *sz;
  size_t nv, nf, counts[3];
  TpMesh *mesh = NULL;
  grid(3, 2, &v, &nv, &idx, &sz, &nf);

  CHECK(tp_mesh_new(v, nv, idx, 4 * nf, sz, nf, &mesh) == TP_OK && mesh != NULL);
  CHECK(tp_last_error_message(NULL, 0) == 0);
  CHECK(tp_mesh_counts(mesh, &counts[0], &counts[1], &counts[2]) == TP_OK);
  CHECK(counts[0] == 12 && counts[1] == 6 && counts[2] == 24);
  CHECK(tp_mesh_counts(mesh, NULL, &counts[1], NULL) == TP_OK);

  double back[36];
  uint32_t back_idx[24], back_sz[6];
  CHECK(tp_mesh_copy_vertices(mesh, back, 36) == TP_OK && memcmp(back, v, sizeof back) == 0);
  CHECK(tp_mesh_copy_vertices(mesh, back, 35) == TP_BUFFER_TOO_SMALL);
  CHECK(last_error_contains("35"));
  CHECK(tp_mesh_copy_vertices(mesh, NULL, 36) == TP_NULL_POINTER);
  CHECK(tp_mesh_copy_faces(mesh, back_idx, 24, back_sz, 6) == TP_OK);
  CHECK(memcmp(back_idx, idx, sizeof back_idx) == 0 && back_sz[5] == 4);
  CHECK(tp_mesh_copy_faces(mesh, back_idx, 24, back_sz, 5) == TP_BUFFER_TOO_SMALL);
  CHECK(tp_mesh_counts(NULL, &counts[0], NULL, NULL) == TP_NULL_POINTER);
  tp_mesh_free(mesh);

  /* Error paths: each names its culprit, and never writes *out. */
  TpMesh *none = NULL;
  CHECK(tp_mesh_new(v, nv, idx, 4 * nf, sz, nf, NULL) == TP_NULL_POINTER);
  CHECK(tp_mesh_new(NULL, nv, idx, 4 * nf, sz, nf, &none) == TP_NULL_POINTER && none == NULL);
  CHECK(last_error_contains("vertices"));
  CHECK(tp_mesh_new(v, nv, idx, 4 * nf - 1, sz, nf, &none) == TP_INVALID_ARGUMENT && none == NULL);
  CHECK(tp_mesh_new(v, 0, idx, 0, sz, 0, &none) == TP_INVALID_MESH && last_error_contains("empty"));
  CHECK(tp_mesh_new(v, (size_t)-1, idx, 4 * nf, sz, nf, &none) == TP_INVALID_ARGUMENT);

  v[3 * 5 + 1] = NAN;
  CHECK(tp_mesh_new(v, nv, idx, 4 * nf, sz, nf, &none) == TP_INVALID_MESH && last_error_contains("vertex 5"));
  v[3 * 5 + 1] = INFINITY;
  CHECK(tp_mesh_new(v, nv, idx, 4 * nf, sz, nf, &none) == TP_INVALID_MESH);
  v[3 * 5 + 1] = 1.0;

  idx[4 * 2 + 1] = 99;
  CHECK(tp_mesh_new(v, nv, idx, 4 * nf, sz, nf, &none) == TP_INVALID_MESH && last_error_contains("face 2"));
  idx[4 * 2 + 1] = idx[4 * 2];
  CHECK(tp_mesh_new(v, nv, idx, 4 * nf, sz, nf, &none) == TP_INVALID_MESH && last_error_contains("more than once"));
  free(v);
  free(idx);
  free(sz);

  /* Three triangles on one edge: non-manifold. */
  double tv[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1};
  uint32_t ti[] = {0, 1, 2, 1, 0, 3, 0, 1, 4}, ts[] = {3, 3, 3};
  CHECK(tp_mesh_new(tv, 5, ti, 9, ts, 3, &none) == TP_INVALID_MESH && last_error_contains("shared by 3"));
  uint32_t two[] = {2};
  CHECK(tp_mesh_new(tv, 5, ti, 2, two, 1, &none) == TP_INVALID_MESH && last_error_contains("at least 3"));
  CHECK(none == NULL);
  tp_mesh_free(NULL);
}

/* A mesh as hosts give it (ABI 10): the 3 x 2 grid as a soup of quads, each with its own four
   corners and the third turned over, welded as the command line reads a file. */
static void test_mesh_welded(void) {
  double *v;
  uint32_t *idx, *sz;
  size_t nv, nf, counts[3];
  grid(3, 2, &v, &nv, &idx, &sz, &nf);
  double soup[6 * 4 * 3];
  uint32_t own[24];
  for (size_t f = 0; f < nf; f++)
    for (size_t k = 0; k < 4; k++) {
      size_t corner = f == 2 ? 3 - k : k; /* face 2 wound the other way */
      memcpy(soup + 3 * (4 * f + k), v + 3 * idx[4 * f + corner], 3 * sizeof(double));
      own[4 * f + k] = (uint32_t)(4 * f + k);
    }
  TpMesh *apart = NULL, *welded = NULL;
  /* As given: six pieces, and face 2 against its neighbours is only seen once joined. */
  CHECK(tp_mesh_new(soup, 24, own, 24, sz, nf, &apart) == TP_OK);
  CHECK(tp_mesh_new_welded(soup, 24, own, 24, sz, nf, 1e-6, &welded) == TP_OK);
  CHECK(tp_mesh_counts(welded, &counts[0], &counts[1], &counts[2]) == TP_OK);
  CHECK(counts[0] == 12 && counts[1] == 6 && counts[2] == 24);
  uint32_t vs[24], fs[6], faces[24], sizes[6];
  CHECK(tp_mesh_copy_sources(welded, vs, 12, fs, 6) == TP_OK);
  CHECK(tp_mesh_copy_faces(welded, faces, 24, sizes, 6) == TP_OK);
  double xyz[36];
  CHECK(tp_mesh_copy_vertices(welded, xyz, 36) == TP_OK);
  for (size_t f = 0; f < 6; f++) CHECK(fs[f] == f);
  /* Each vertex is where its first given vertex is. */
  for (size_t i = 0; i < 12; i++) CHECK(vs[i] < 24 && memcmp(xyz + 3 * i, soup + 3 * vs[i], 3 * sizeof(double)) == 0);
  /* Face 2 turned to agree with the others: every face wound counter-clockwise seen from +z,
     as the grid's are. */
  for (size_t f = 0; f < 6; f++) {
    const double *a = xyz + 3 * faces[4 * f], *b = xyz + 3 * faces[4 * f + 1], *c = xyz + 3 * faces[4 * f + 2];
    CHECK((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]) > 0.0);
  }
  CHECK(tp_mesh_copy_sources(welded, vs, 11, NULL, 0) == TP_BUFFER_TOO_SMALL);
  /* A mesh of tp_mesh_new is its own source. */
  CHECK(tp_mesh_copy_sources(apart, vs, 24, NULL, 0) == TP_OK && vs[23] == 23);
  /* 0 joins nothing; a bad tolerance is refused by name. */
  TpMesh *none = NULL;
  CHECK(tp_mesh_new_welded(soup, 24, own, 24, sz, nf, 0.0, &none) == TP_OK);
  CHECK(tp_mesh_counts(none, &counts[0], NULL, NULL) == TP_OK && counts[0] == 24);
  tp_mesh_free(none);
  none = NULL;
  CHECK(tp_mesh_new_welded(soup, 24, own, 24, sz, nf, NAN, &none) == TP_INVALID_ARGUMENT && none == NULL);
  CHECK(last_error_contains("relative_tolerance"));
  CHECK(tp_mesh_new_welded(soup, 24, own, 24, sz, nf, 1e-6, NULL) == TP_NULL_POINTER);
  printf("mesh welded: 24 vertices of a soup of 6 quads -> 12, face 2 turned\n");
  tp_mesh_free(apart);
  tp_mesh_free(welded);
  free(v);
  free(idx);
  free(sz);
}

static void test_pattern_and_tiles(void) {
  TpMesh *mesh = grid_mesh(10, 10);
  CHECK(mesh != NULL);
  TpPatternOptions options = tp_pattern_options_default();
  CHECK(options.struct_size == sizeof(TpPatternOptions) && options.bond == TP_BOND_STAGGERED);
  options.weight = 2.0;
  TpPattern *pattern = NULL;
  CHECK(tp_pattern_solve(mesh, &options, NULL, NULL, &pattern) == TP_OK);
  TpPatternSummary summary;
  CHECK(tp_pattern_summary(pattern, &summary) == TP_OK);
  /* Paper, Figure 5: 49 tiles, no continuous joint, proven. */
  CHECK(summary.pairs == 49 && summary.unpaired == 2 && summary.continuous_joints == 0);
  CHECK(summary.status == TP_SOLVE_OPTIMAL && summary.objective == 49.0 && summary.bound == 49.0);
  /* 49 < 50 tiles of a perfect matching: no matching proves it, the star rows' linear
     relaxation does (the paper's route, TP_METHOD_MIP, proves it by branch and bound). */
  int32_t source = -1;
  CHECK(tp_pattern_bound_source(pattern, &source) == TP_OK && source == TP_BOUND_LINEAR_RELAXATION);
  TpPatternOptions paper = options;
  paper.method = TP_METHOD_MIP;
  TpPattern *by_paper = NULL;
  CHECK(tp_pattern_solve(mesh, &paper, NULL, NULL, &by_paper) == TP_OK);
  CHECK(tp_pattern_bound_source(by_paper, &source) == TP_OK && source == TP_BOUND_WHOLE_PROGRAM);
  tp_pattern_free(by_paper);
  CHECK(tp_pattern_bound_source(NULL, &source) == TP_NULL_POINTER);
  CHECK(tp_pattern_bound_source(pattern, NULL) == TP_NULL_POINTER);
  uint32_t pairs[98], unpaired[2];
  CHECK(tp_pattern_copy_pairs(pattern, pairs, 98) == TP_OK);
  CHECK(tp_pattern_copy_pairs(pattern, pairs, 97) == TP_BUFFER_TOO_SMALL);
  CHECK(tp_pattern_copy_unpaired(pattern, unpaired, 2) == TP_OK && unpaired[0] < 100);
  int adjacent = 1;
  for (int k = 0; k < 49; k++) {
    uint32_t a = pairs[2 * k], b = pairs[2 * k + 1];
    adjacent &= (b == a + 1 && a % 10 != 9) || b == a + 10;
  }
  CHECK(adjacent);

  /* Tiles: 1.9 x 0.95 x 0.1 on unit quads, placed as in the paper (section 3.5). */
  TpTileOptions tile = tp_tile_options_default();
  CHECK(tile.length == 0.28 && tile.fit == 1);
  tile.fit = 0;
  tile.length = 1.9;
  tile.width = 0.95;
  tile.thickness = 0.1;
  tile.joint = 0.1;
  TpTiles *tiles = NULL;
  CHECK(tp_tiles_build(mesh, pattern, &tile, &tiles) == TP_OK);
  size_t count = 0;
  CHECK(tp_tiles_count(tiles, &count) == TP_OK && count == 51);
  int32_t kinds[51];
  double corners[51 * 24], frames[51 * 12], sizes[51 * 3];
  uint32_t faces[51 * 2];
  CHECK(tp_tiles_copy_kinds(tiles, kinds, 51) == TP_OK && kinds[0] == TP_TILE_FULL && kinds[50] == TP_TILE_HALF);
  CHECK(tp_tiles_copy_corners(tiles, corners, 51 * 24) == TP_OK);
  CHECK(tp_tiles_copy_corners(tiles, corners, 51 * 24 - 1) == TP_BUFFER_TOO_SMALL);
  CHECK(tp_tiles_copy_frames(tiles, frames, 51 * 12) == TP_OK && fabs(frames[11] - 1.0) < 1e-12);
  CHECK(tp_tiles_copy_sizes(tiles, sizes, 51 * 3) == TP_OK && sizes[0] == 1.9 && sizes[50 * 3] == 0.95);
  CHECK(tp_tiles_copy_faces(tiles, faces, 51 * 2) == TP_OK && faces[101] == TP_NO_FACE);
  CHECK(corners[2] == 0.0 && corners[4 * 3 + 2] == 0.1);

  size_t needed = 0;
  CHECK(tp_tiles_report_json(tiles, NULL, 0, &needed) == TP_BUFFER_TOO_SMALL && needed > 100);
  char *json = (char *)malloc(needed + 1);
  CHECK(tp_tiles_report_json(tiles, json, needed + 1, NULL) == TP_OK);
  CHECK(strlen(json) == needed && strstr(json, "\"full_tiles\": 49") != NULL);
  free(json);
  tp_tiles_free(tiles);

  /* Options initialisers write no more than the caller's struct: an ABI 1 caller's
     TpTileOptions ended before cut_tolerance. */
  {
    unsigned char buffer[sizeof(TpTileOptions) + 16];
    memset(buffer, 0xAB, sizeof buffer);
    size_t old_size = offsetof(TpTileOptions, cut_tolerance);
    CHECK(tp_tile_options_init((TpTileOptions *)(void *)buffer, old_size) == TP_OK);
    int untouched = 1;
    for (size_t b = old_size; b < sizeof buffer; b++) untouched &= buffer[b] == 0xAB;
    TpTileOptions read_back;
    memcpy(&read_back, buffer, old_size);
    CHECK(untouched && read_back.struct_size == old_size && read_back.length == 0.28 && read_back.joint == 0.01);
    TpTileOptions full;
    CHECK(tp_tile_options_init(&full, sizeof full) == TP_OK && full.struct_size == sizeof full && full.up[2] == 1.0);
    TpPatternOptions pattern_options;
    TpRemeshOptions remesh_options;
    CHECK(tp_pattern_options_init(&pattern_options, sizeof pattern_options) == TP_OK && pattern_options.bond == TP_BOND_STAGGERED);
    CHECK(tp_remesh_options_init(&remesh_options, sizeof remesh_options) == TP_OK && remesh_options.target_edge > 0.0);
    CHECK(tp_tile_options_init(NULL, sizeof full) == TP_NULL_POINTER);
    CHECK(tp_tile_options_init(&full, 2) == TP_INVALID_ARGUMENT && last_error_contains("size 2"));
  }

  /* Boundary tiles: cut to a surface that ends at x = 6.5 (the quads reach x = 10). */
  {
    double *sv;
    uint32_t *sidx, *ssz;
    size_t snv, snf;
    grid(13, 20, &sv, &snv, &sidx, &ssz, &snf);
    for (size_t k = 0; k < snv; k++) {
      sv[3 * k] *= 0.5;
      sv[3 * k + 1] *= 0.5;
    }
    TpMesh *surface = NULL;
    CHECK(tp_mesh_new(sv, snv, sidx, 4 * snf, ssz, snf, &surface) == TP_OK);
    free(sv);
    free(sidx);
    free(ssz);
    TpTiles *cut = NULL;
    CHECK(tp_tiles_build_on_surface(mesh, pattern, surface, &tile, &cut) == TP_OK);
    size_t n = 0, loops = 0, points = 0;
    CHECK(tp_tiles_count(cut, &n) == TP_OK && n > 20 && n < 51);
    int32_t *k = (int32_t *)malloc(n * sizeof(int32_t));
    uint32_t *steps = (uint32_t *)malloc(n * sizeof(uint32_t)), *loop_counts = (uint32_t *)malloc(n * sizeof(uint32_t));
    double *kept = (double *)malloc(n * sizeof(double));
    CHECK(tp_tiles_copy_kinds(cut, k, n) == TP_OK);
    CHECK(tp_tiles_copy_steps(cut, steps, n) == TP_OK);
    CHECK(tp_tiles_copy_kept_fractions(cut, kept, n) == TP_OK);
    CHECK(tp_tiles_copy_loop_counts(cut, loop_counts, n) == TP_OK);
    CHECK(tp_tiles_outline_counts(cut, &loops, &points) == TP_OK && loops > 0 && points >= 3 * loops);
    CHECK(tp_tiles_outline_counts(cut, NULL, &points) == TP_OK);
    size_t boundary = 0, loop_sum = 0, step_sum = 0;
    int fractions_ok = 1;
    for (size_t t = 0; t < n; t++) {
      boundary += k[t] == TP_TILE_BOUNDARY;
      loop_sum += loop_counts[t];
      step_sum += steps[t];
      fractions_ok &= kept[t] > 0.0 && kept[t] <= 1.0 && (k[t] == TP_TILE_BOUNDARY) == (kept[t] < 1.0);
    }
    CHECK(boundary > 0 && loop_sum == loops && fractions_ok);
    CHECK(step_sum == n * (n - 1) / 2);
    uint32_t *sizes_of_loops = (uint32_t *)malloc(loops * sizeof(uint32_t));
    double *xy = (double *)malloc(2 * points * sizeof(double));
    CHECK(tp_tiles_copy_loop_sizes(cut, sizes_of_loops, loops) == TP_OK);
    CHECK(tp_tiles_copy_loop_points(cut, xy, 2 * points) == TP_OK);
    CHECK(tp_tiles_copy_loop_points(cut, xy, 2 * points - 1) == TP_BUFFER_TOO_SMALL);
    size_t point_sum = 0;
    for (size_t l = 0; l < loops; l++) point_sum += sizes_of_loops[l];
    CHECK(point_sum == points);
    size_t text = 0;
    CHECK(tp_tiles_labels(cut, NULL, 0, &text) == TP_BUFFER_TOO_SMALL && text >= 2 * n);
    char *labels = (char *)malloc(text + 1);
    CHECK(tp_tiles_labels(cut, labels, text + 1, NULL) == TP_OK && strstr(labels, "B1\n") != NULL);
    CHECK(tp_tiles_cutlist_json(cut, NULL, 0, &text) == TP_BUFFER_TOO_SMALL);
    char *cutlist = (char *)malloc(text + 1);
    CHECK(tp_tiles_cutlist_json(cut, cutlist, text + 1, NULL) == TP_OK && strstr(cutlist, "\"label\": \"B1\"") != NULL);
    free(k);
    free(steps);
    free(loop_counts);
    free(kept);
    free(sizes_of_loops);
    free(xy);
    free(labels);
    free(cutlist);
    tp_tiles_free(cut);
    CHECK(tp_tiles_build_on_surface(mesh, pattern, NULL, &tile, &cut) == TP_OK);
    CHECK(tp_tiles_count(cut, &n) == TP_OK && n == 51);
    tp_tiles_free(cut);
    tp_mesh_free(surface);
  }

  /* Tile errors. */
  TpTiles *none = NULL;
  tile.length = 0.0;
  CHECK(tp_tiles_build(mesh, pattern, &tile, &none) == TP_INVALID_ARGUMENT && last_error_contains("length"));
  tile = tp_tile_options_default();
  tile.struct_size = 0;
  CHECK(tp_tiles_build(mesh, pattern, &tile, &none) == TP_INVALID_ARGUMENT && last_error_contains("struct_size"));
  TpMesh *small = grid_mesh(3, 3);
  tile = tp_tile_options_default();
  CHECK(tp_tiles_build(small, pattern, &tile, &none) == TP_INVALID_PATTERN);
  CHECK(tp_tiles_build(NULL, pattern, &tile, &none) == TP_NULL_POINTER && none == NULL);
  tp_mesh_free(small);
  tp_tiles_free(NULL);

  /* Pattern errors. */
  TpPattern *bad = NULL;
  options = tp_pattern_options_default();
  options.bond = 7;
  CHECK(tp_pattern_solve(mesh, &options, NULL, NULL, &bad) == TP_INVALID_ARGUMENT && last_error_contains("bond 7"));
  options = tp_pattern_options_default();
  options.weight = NAN;
  CHECK(tp_pattern_solve(mesh, &options, NULL, NULL, &bad) == TP_INVALID_ARGUMENT);
  options = tp_pattern_options_default();
  options.time_limit_seconds = -1.0;
  CHECK(tp_pattern_solve(mesh, &options, NULL, NULL, &bad) == TP_INVALID_ARGUMENT && last_error_contains("time limit"));
  options = tp_pattern_options_default();
  uint32_t far_pair[] = {0, 55};
  options.forced_pairs = far_pair;
  options.forced_pair_count = 1;
  CHECK(tp_pattern_solve(mesh, &options, NULL, NULL, &bad) == TP_INVALID_ARGUMENT && last_error_contains("[0, 55]"));
  options.forced_pairs = NULL;
  CHECK(tp_pattern_solve(mesh, &options, NULL, NULL, &bad) == TP_NULL_POINTER);
  options = tp_pattern_options_default();
  uint32_t hole[] = {100};
  options.excluded_faces = hole;
  options.excluded_face_count = 1;
  CHECK(tp_pattern_solve(mesh, &options, NULL, NULL, &bad) == TP_INVALID_ARGUMENT && last_error_contains("face 100"));
  CHECK(tp_pattern_solve(mesh, NULL, NULL, NULL, &bad) == TP_NULL_POINTER && bad == NULL);
  CHECK(tp_pattern_summary(NULL, &summary) == TP_NULL_POINTER);
  CHECK(tp_pattern_summary(pattern, NULL) == TP_NULL_POINTER);

  /* Forced pairs and exclusions work; a caller with an older, shorter struct gets defaults. */
  options = tp_pattern_options_default();
  uint32_t forced[] = {0, 10};
  uint32_t excluded[] = {99};
  options.forced_pairs = forced;
  options.forced_pair_count = 1;
  options.excluded_faces = excluded;
  options.excluded_face_count = 1;
  TpPattern *constrained = NULL;
  CHECK(tp_pattern_solve(mesh, &options, NULL, NULL, &constrained) == TP_OK);
  CHECK(tp_pattern_summary(constrained, &summary) == TP_OK && summary.excluded == 1);
  CHECK(tp_pattern_copy_pairs(constrained, pairs, 98) == TP_OK);
  int has_forced = 0;
  for (size_t k = 0; k < summary.pairs; k++) has_forced |= pairs[2 * k] == 0 && pairs[2 * k + 1] == 10;
  CHECK(has_forced);
  tp_pattern_free(constrained);

  options = tp_pattern_options_default();
  options.struct_size = (uint32_t)offsetof(TpPatternOptions, time_limit_seconds);
  options.bond = TP_BOND_STACK;
  options.time_limit_seconds = -5.0; /* beyond the old struct: ignored, default used */
  CHECK(tp_pattern_solve(mesh, &options, NULL, NULL, &constrained) == TP_OK);
  CHECK(tp_pattern_summary(constrained, &summary) == TP_OK && summary.pairs == 50);
  tp_pattern_free(constrained);

  tp_pattern_free(pattern);
  tp_pattern_free(NULL);
  tp_mesh_free(mesh);
}

struct remesh_progress {
  int calls, inside, backwards, stage_ok, calls_after_cancel;
  double first, last, cancel_from;
  int cancelled;
};

static int32_t watch_remesh(void *user, uint32_t stage, double fraction) {
  struct remesh_progress *p = (struct remesh_progress *)user;
  if (p->cancelled) p->calls_after_cancel++;
  if (p->calls == 0) p->first = fraction;
  if (p->calls > 0 && fraction < p->last) p->backwards++;
  p->calls++;
  p->last = fraction;
  p->inside += fraction > 0.0 && fraction < 1.0;
  p->stage_ok += stage == TP_STAGE_REMESH;
  if (p->cancel_from > 0.0 && fraction >= p->cancel_from && fraction < 1.0) {
    p->cancelled = 1;
    return 1;
  }
  return 0;
}

/* Progress during the stage, cancel in the middle of it, the time limit, older structs. */
static void test_remesh_progress(const TpMesh *surface) {
  TpRemeshOptions options = tp_remesh_options_default();
  options.target_edge = 0.2;
  CHECK(options.time_limit_seconds == 60.0);
  TpMesh *quads = NULL;
  struct remesh_progress watch = {0, 0, 0, 0, 0, 0.0, 0.0, 0.0, 0};
  CHECK(tp_remesh(surface, &options, watch_remesh, &watch, &quads) == TP_OK && quads != NULL);
  CHECK(watch.calls >= 3 && watch.first == 0.0 && watch.last == 1.0 && watch.inside >= 1);
  CHECK(watch.backwards == 0 && watch.stage_ok == watch.calls);
  tp_mesh_free(quads);

  /* Cancelled once a fifth of the stage is done: no mesh, no further callbacks. */
  quads = NULL;
  struct remesh_progress cancel = {0, 0, 0, 0, 0, 0.0, 0.0, 0.2, 0};
  CHECK(tp_remesh(surface, &options, watch_remesh, &cancel, &quads) == TP_CANCELLED && quads == NULL);
  CHECK(last_error_contains("cancelled"));
  CHECK(cancel.cancelled && cancel.last >= 0.2 && cancel.last < 1.0 && cancel.calls_after_cancel == 0);

  /* No time at all: nothing to return. A negative limit is refused. */
  options.time_limit_seconds = 0.0;
  CHECK(tp_remesh(surface, &options, NULL, NULL, &quads) == TP_TIME_LIMIT && quads == NULL);
  CHECK(last_error_contains("time limit"));
  options.time_limit_seconds = -1.0;
  CHECK(tp_remesh(surface, &options, NULL, NULL, &quads) == TP_INVALID_ARGUMENT && last_error_contains("time limit"));
  options.time_limit_seconds = NAN;
  CHECK(tp_remesh(surface, &options, NULL, NULL, &quads) == TP_INVALID_ARGUMENT && quads == NULL);

  /* A caller compiled before time_limit_seconds existed gets the default limit. */
  options.struct_size = (uint32_t)offsetof(TpRemeshOptions, time_limit_seconds);
  options.time_limit_seconds = -5.0;
  CHECK(tp_remesh(surface, &options, NULL, NULL, &quads) == TP_OK && quads != NULL);
  tp_mesh_free(quads);
}

/* Mean |cos 4 theta| of the edges of a flat quad mesh against the direction at `degrees`
   (1 when every edge is on the direction or across it). */
static double edge_alignment(const TpMesh *quads, double degrees) {
  size_t nv = 0, nf = 0, ni = 0;
  CHECK(tp_mesh_counts(quads, &nv, &nf, &ni) == TP_OK);
  double *v = (double *)malloc(3 * nv * sizeof(double));
  uint32_t *idx = (uint32_t *)malloc(ni * sizeof(uint32_t)), *sz = (uint32_t *)malloc(nf * sizeof(uint32_t));
  CHECK(tp_mesh_copy_vertices(quads, v, 3 * nv) == TP_OK);
  CHECK(tp_mesh_copy_faces(quads, idx, ni, sz, nf) == TP_OK);
  double sum = 0.0, a = degrees * 3.14159265358979323846 / 180.0;
  size_t k = 0;
  for (size_t f = 0; f < nf; f++) {
    for (uint32_t c = 0; c < sz[f]; c++) {
      const double *p = v + 3 * idx[k + c], *q = v + 3 * idx[k + (c + 1) % sz[f]];
      double theta = atan2(q[1] - p[1], q[0] - p[0]) - a;
      sum += fabs(cos(4.0 * theta));
    }
    k += sz[f];
  }
  free(v);
  free(idx);
  free(sz);
  return sum / (double)ni;
}

/* The designer's field: one vector per face (or vertex), validated with the index at fault;
   an older struct without the field keeps working. */
static void test_remesh_field(const TpMesh *surface, size_t vertices, size_t faces) {
  double *field = (double *)malloc(3 * faces * sizeof(double));
  const double a = 30.0 * 3.14159265358979323846 / 180.0;
  for (size_t f = 0; f < faces; f++) {
    double sign = f % 2 ? -2.0 : 1.0;
    field[3 * f] = sign * cos(a);
    field[3 * f + 1] = sign * sin(a);
    field[3 * f + 2] = 0.0;
  }
  TpRemeshOptions options;
  CHECK(tp_remesh_options_init(&options, sizeof options) == TP_OK);
  CHECK(options.field_vectors == NULL && options.field_count == 0 && options.field_weight == 1.0);
  options.target_edge = 0.2;
  TpMesh *plain = NULL, *turned = NULL, *again = NULL;
  CHECK(tp_remesh(surface, &options, NULL, NULL, &plain) == TP_OK);
  options.field_vectors = field;
  options.field_count = faces;
  CHECK(tp_remesh(surface, &options, NULL, NULL, &turned) == TP_OK);
  CHECK(tp_remesh(surface, &options, NULL, NULL, &again) == TP_OK);
  double on_plain = edge_alignment(plain, 30.0), on_turned = edge_alignment(turned, 30.0);
  printf("remesh field: edges on the 30 degree field %.3f without, %.3f with it\n", on_plain, on_turned);
  CHECK(on_turned > on_plain + 0.2);
  CHECK(edge_alignment(again, 30.0) == on_turned);
  tp_mesh_free(plain);
  tp_mesh_free(turned);
  tp_mesh_free(again);

  TpMesh *none = NULL;
  options.field_count = faces - 1;
  CHECK(tp_remesh(surface, &options, NULL, NULL, &none) == TP_INVALID_ARGUMENT && none == NULL);
  CHECK(last_error_contains("vertices") && last_error_contains("faces"));
  options.field_count = faces;
  field[3 * 7] = NAN;
  CHECK(tp_remesh(surface, &options, NULL, NULL, &none) == TP_INVALID_ARGUMENT && last_error_contains("face 7"));
  field[3 * 7] = field[3 * 7 + 1] = 0.0;
  CHECK(tp_remesh(surface, &options, NULL, NULL, &none) == TP_INVALID_ARGUMENT && last_error_contains("face 7"));
  field[3 * 7] = 1.0;
  options.field_weight = 1.5;
  CHECK(tp_remesh(surface, &options, NULL, NULL, &none) == TP_INVALID_ARGUMENT && last_error_contains("weight"));
  options.field_weight = 1.0;
  options.field_vectors = NULL;
  CHECK(tp_remesh(surface, &options, NULL, NULL, &none) == TP_NULL_POINTER && last_error_contains("field_vectors"));
  /* Per vertex: the count decides. */
  options.field_vectors = field;
  options.field_count = vertices;
  CHECK(tp_remesh(surface, &options, NULL, NULL, &none) == TP_OK && none != NULL);
  tp_mesh_free(none);
  none = NULL;
  /* A caller compiled before the field existed: whatever lies past its struct is ignored. */
  options.struct_size = (uint32_t)offsetof(TpRemeshOptions, field_vectors);
  options.field_count = 3;
  CHECK(tp_remesh(surface, &options, NULL, NULL, &none) == TP_OK && none != NULL);
  tp_mesh_free(none);
  free(field);
}

/* Guide curves (ABI 6): two polylines at 30 degrees through the plate, validated with the
   curve and point at fault; a caller built against ABI 5 keeps working. */
static void test_remesh_guides(const TpMesh *surface) {
  const double a = 30.0 * 3.14159265358979323846 / 180.0;
  /* Curve 0: three points through the centre (1, 1); curve 1: two points near a corner. */
  double points[5 * 3] = {
      1.0 - 1.1 * cos(a), 1.0 - 1.1 * sin(a), 0.0, 1.0, 1.0, 0.0, 1.0 + 1.1 * cos(a), 1.0 + 1.1 * sin(a), 0.0,
      0.1, 0.1, 0.0, 0.1 + 0.3 * cos(a), 0.1 + 0.3 * sin(a), 0.0,
  };
  uint32_t sizes[2] = {3, 2};
  TpRemeshOptions options;
  CHECK(tp_remesh_options_init(&options, sizeof options) == TP_OK);
  CHECK(options.guide_points == NULL && options.guide_point_count == 0 && options.guide_curve_sizes == NULL &&
        options.guide_count == 0 && options.guide_weight == 1.0);
  options.target_edge = 0.2;
  TpMesh *plain = NULL, *guided = NULL, *again = NULL;
  CHECK(tp_remesh(surface, &options, NULL, NULL, &plain) == TP_OK);
  options.guide_points = points;
  options.guide_point_count = 5;
  options.guide_curve_sizes = sizes;
  options.guide_count = 2;
  CHECK(tp_remesh(surface, &options, NULL, NULL, &guided) == TP_OK);
  CHECK(tp_remesh(surface, &options, NULL, NULL, &again) == TP_OK);
  double on_plain = edge_alignment(plain, 30.0), on_guided = edge_alignment(guided, 30.0);
  printf("remesh guides: edges on the 30 degree guides %.3f without, %.3f with them\n", on_plain, on_guided);
  CHECK(on_guided > on_plain + 0.2);
  CHECK(edge_alignment(again, 30.0) == on_guided);
  tp_mesh_free(plain);
  tp_mesh_free(guided);
  tp_mesh_free(again);

  TpMesh *none = NULL;
  options.guide_point_count = 4;
  CHECK(tp_remesh(surface, &options, NULL, NULL, &none) == TP_INVALID_ARGUMENT && none == NULL);
  CHECK(last_error_contains("add up to 5 points") && last_error_contains("guide_point_count is 4"));
  sizes[0] = 4;
  sizes[1] = 1;
  options.guide_point_count = 5;
  CHECK(tp_remesh(surface, &options, NULL, NULL, &none) == TP_INVALID_ARGUMENT && last_error_contains("guide curve 1 has 1 point"));
  sizes[0] = 3;
  sizes[1] = 2;
  points[3 * 1 + 2] = NAN;
  CHECK(tp_remesh(surface, &options, NULL, NULL, &none) == TP_INVALID_ARGUMENT && last_error_contains("point 1 of guide curve 0"));
  points[3 * 1 + 2] = 0.0;
  points[3 * 3 + 2] = points[3 * 4 + 2] = 5.0;
  CHECK(tp_remesh(surface, &options, NULL, NULL, &none) == TP_INVALID_ARGUMENT && last_error_contains("guide curve 1 is nowhere near"));
  points[3 * 3 + 2] = points[3 * 4 + 2] = 0.0;
  options.guide_weight = 1.5;
  CHECK(tp_remesh(surface, &options, NULL, NULL, &none) == TP_INVALID_ARGUMENT && last_error_contains("guide weight"));
  options.guide_weight = 1.0;
  options.guide_points = NULL;
  CHECK(tp_remesh(surface, &options, NULL, NULL, &none) == TP_NULL_POINTER && last_error_contains("guide_points"));
  options.guide_points = points;
  options.guide_curve_sizes = NULL;
  CHECK(tp_remesh(surface, &options, NULL, NULL, &none) == TP_NULL_POINTER && last_error_contains("guide_curve_sizes"));
  CHECK(none == NULL);
  /* A caller built against ABI 5: whatever lies past its struct is ignored. */
  options.struct_size = (uint32_t)offsetof(TpRemeshOptions, guide_points);
  options.guide_count = 7;
  CHECK(tp_remesh(surface, &options, NULL, NULL, &none) == TP_OK && none != NULL);
  tp_mesh_free(none);
}

static void test_remesh(void) {
  /* A flat 2 x 2 square split into 800 triangles, remeshed with quads of edge 0.2. */
  double *v;
  uint32_t *quad_idx, *quad_sz;
  size_t nv, nf;
  grid(20, 20, &v, &nv, &quad_idx, &quad_sz, &nf);
  for (size_t k = 0; k < 3 * nv; k++) v[k] *= 0.1;
  uint32_t *tri = (uint32_t *)malloc(nf * 6 * sizeof(uint32_t)), *tri_sz = (uint32_t *)malloc(nf * 2 * sizeof(uint32_t));
  for (size_t f = 0; f < nf; f++) {
    uint32_t *q = quad_idx + 4 * f, *t = tri + 6 * f;
    t[0] = q[0]; t[1] = q[1]; t[2] = q[2];
    t[3] = q[0]; t[4] = q[2]; t[5] = q[3];
    tri_sz[2 * f] = tri_sz[2 * f + 1] = 3;
  }
  TpMesh *surface = NULL, *quads = NULL;
  CHECK(tp_mesh_new(v, nv, tri, 6 * nf, tri_sz, 2 * nf, &surface) == TP_OK);
  TpRemeshOptions options = tp_remesh_options_default();
  options.target_edge = 0.2;
  CHECK(tp_remesh(surface, &options, NULL, NULL, &quads) == TP_OK && quads != NULL);
  size_t counts[3] = {0, 0, 0};
  CHECK(tp_mesh_counts(quads, &counts[0], &counts[1], &counts[2]) == TP_OK);
  CHECK(counts[1] > 50 && counts[1] < 200 && counts[2] == 4 * counts[1]);
  tp_mesh_free(quads);
  /* The smooth field (TP_DIRECTION_SMOOTH): on a flat square, whose boundary alone
     orients the quads, the same count. */
  quads = NULL;
  options.direction = TP_DIRECTION_SMOOTH;
  size_t smooth[3] = {0, 0, 0};
  CHECK(tp_remesh(surface, &options, NULL, NULL, &quads) == TP_OK && quads != NULL);
  CHECK(tp_mesh_counts(quads, &smooth[0], &smooth[1], &smooth[2]) == TP_OK);
  CHECK(smooth[1] == counts[1]);
  tp_mesh_free(quads);

  quads = NULL;
  options.direction = TP_DIRECTION_CURVATURE;
  options.target_edge = 0.0;
  CHECK(tp_remesh(surface, &options, NULL, NULL, &quads) == TP_INVALID_ARGUMENT && quads == NULL);
  options = tp_remesh_options_default();
  options.direction = 9;
  CHECK(tp_remesh(surface, &options, NULL, NULL, &quads) == TP_INVALID_ARGUMENT && last_error_contains("direction 9"));
  CHECK(tp_remesh(NULL, &options, NULL, NULL, &quads) == TP_NULL_POINTER);
  CHECK(tp_remesh(surface, &options, NULL, NULL, NULL) == TP_NULL_POINTER);
  test_remesh_field(surface, nv, 2 * nf);
  test_remesh_guides(surface);
  test_remesh_progress(surface);
  tp_mesh_free(surface);
  free(v);
  free(quad_idx);
  free(quad_sz);
  free(tri);
  free(tri_sz);
}

struct cancel_state {
  double start, cancel_after, cancelled_at;
  int calls, last_stage;
};

static int32_t cancel_later(void *user, uint32_t stage, double fraction) {
  struct cancel_state *s = (struct cancel_state *)user;
  s->calls++;
  s->last_stage = (int)stage;
  (void)fraction;
  /* Keep going for a while and at least one callback, however slow the machine. */
  if (s->calls < 2 || now_seconds() - s->start < s->cancel_after) return 0;
  if (s->cancelled_at == 0.0) s->cancelled_at = now_seconds();
  return 1;
}

static void test_cancel_and_time_limit(void) {
  TpMesh *mesh = grid_mesh(100, 100);
  TpPatternOptions options = tp_pattern_options_default();
  struct cancel_state state = {now_seconds(), 0.5, 0.0, 0, 0};
  TpPattern *pattern = NULL;
  TpStatus s = tp_pattern_solve(mesh, &options, cancel_later, &state, &pattern);
  double returned = now_seconds();
  CHECK(s == TP_CANCELLED && pattern == NULL && last_error_contains("cancelled"));
  CHECK(state.calls > 1 && state.last_stage == TP_STAGE_PATTERN);
  printf("cancel: returned %.3f s after the callback asked (%d callbacks)\n", returned - state.cancelled_at, state.calls);
  CHECK(state.cancelled_at > 0.0 && returned - state.cancelled_at < 1.0);

  /* A time limit returns a valid pattern with an honest status. */
  options.time_limit_seconds = 0.5;
  CHECK(tp_pattern_solve(mesh, &options, NULL, NULL, &pattern) == TP_OK);
  TpPatternSummary summary;
  CHECK(tp_pattern_summary(pattern, &summary) == TP_OK);
  CHECK(summary.status == TP_SOLVE_TIME_LIMIT && summary.bound >= summary.objective && summary.pairs > 4000);
  tp_pattern_free(pattern);
  tp_mesh_free(mesh);
}

/* How much slower than native this run is: 1, or TP_TEST_TIME_SCALE (the Makefile sets it for
   the run under valgrind, which is tens of times slower). */
static double time_scale(void) {
  const char *scale = getenv("TP_TEST_TIME_SCALE");
  double value = scale != NULL ? atof(scale) : 1.0;
  return value >= 1.0 ? value : 1.0;
}

/* The paper's whole program on CBC for a 12 x 12 grid; its time in seconds (negative when it
   does not end proven optimal). */
static double timed_small_mip(const TpMesh *small) {
  TpPatternOptions options = tp_pattern_options_default();
  options.method = TP_METHOD_MIP;
  options.time_limit_seconds = 60.0;
  TpPattern *pattern = NULL;
  double start = now_seconds();
  TpStatus s = tp_pattern_solve(small, &options, NULL, NULL, &pattern);
  double took = now_seconds() - start;
  TpPatternSummary summary;
  int optimal = s == TP_OK && tp_pattern_summary(pattern, &summary) == TP_OK && summary.status == TP_SOLVE_OPTIMAL;
  tp_pattern_free(pattern);
  return optimal ? took : -1.0;
}

/* Cancel from the progress callback in the middle of the whole program on CBC (the paper's
   route; 45 x 45 grid, 2025 faces, whose root linear program alone takes CBC seconds) returns
   within 0.2 s and leaves CBC free: a CBC solve right after takes as long as the same solve
   did before the cancel. */
static void test_cancel_inside_cbc(void) {
  double scale = time_scale();
  TpMesh *small = grid_mesh(12, 12);
  TpMesh *big = grid_mesh(45, 45);
  double before = timed_small_mip(small);
  CHECK(before > 0.0);

  TpPatternOptions options = tp_pattern_options_default();
  options.method = TP_METHOD_MIP;
  /* The limit scales with the machine: under valgrind writing the program alone can take
     longer than a minute, and a limit reached before CBC starts ends the solve with a pattern
     instead of the cancel this test is about. */
  options.time_limit_seconds = 60.0 * scale;
  /* The callbacks of this solve come only while CBC runs (after the program is written):
     cancel at the first one from 1 s on. */
  struct cancel_state state = {now_seconds(), 1.0, 0.0, 0, 0};
  TpPattern *pattern = NULL;
  TpStatus s = tp_pattern_solve(big, &options, cancel_later, &state, &pattern);
  double returned = now_seconds();
  CHECK(s == TP_CANCELLED && pattern == NULL && last_error_contains("cancelled"));
  tp_pattern_free(pattern); /* NULL when cancelled; freed if the check above failed */
  printf("cancel inside CBC: returned %.3f s after the callback asked, %.2f s into the solve\n",
         returned - state.cancelled_at, state.cancelled_at - state.start);
  CHECK(state.cancelled_at > 0.0 && returned - state.cancelled_at < 0.2 * scale);

  double after = timed_small_mip(small);
  printf("cancel inside CBC: the next solve took %.3f s (%.3f s before the cancel)\n", after, before);
  /* Generous for a loaded machine; a CBC still busy with the cancelled solve would hold the
     next one up for seconds. */
  CHECK(after > 0.0 && after < 2.0 * before + 0.25 * scale);
  tp_mesh_free(small);
  tp_mesh_free(big);
}

/* The tile options of the fit tests: 1.9 x 0.95 x 0.1 tiles, joint 0.1, on unit quads. */
static TpTileOptions fit_tile(void) {
  TpTileOptions tile;
  tp_tile_options_init(&tile, sizeof tile);
  tile.length = 1.9;
  tile.width = 0.95;
  tile.thickness = 0.1;
  tile.joint = 0.1;
  return tile;
}

/* The report of `tiles` as a string (caller frees). */
static char *report_of(const TpTiles *tiles) {
  size_t needed = 0;
  if (tp_tiles_report_json(tiles, NULL, 0, &needed) != TP_BUFFER_TOO_SMALL) return NULL;
  char *json = (char *)malloc(needed + 1);
  if (tp_tiles_report_json(tiles, json, needed + 1, NULL) != TP_OK) {
    free(json);
    return NULL;
  }
  return json;
}

struct fit_progress {
  int calls, other_stage, outside, backwards, cancel_at, calls_after_cancel, cancelled;
  double last;
};

static int32_t watch_fit(void *user, uint32_t stage, double fraction) {
  struct fit_progress *p = (struct fit_progress *)user;
  if (p->cancelled) p->calls_after_cancel++;
  p->other_stage += stage != TP_STAGE_TILES;
  p->outside += !(fraction >= 0.0 && fraction <= 1.0);
  if (p->calls > 0 && fraction < p->last) p->backwards++;
  p->last = fraction;
  p->calls++;
  if (p->cancel_at > 0 && p->calls >= p->cancel_at) {
    p->cancelled = 1;
    return 1;
  }
  return 0;
}

/* The fit stage (stage 3b): on by default, its figures in the report, per-tile joint
 * deviations, progress and cancel through TP_STAGE_TILES, callers with ABI 2 structs. */
static void test_fit(void) {
  TpMesh *mesh = lifted_grid_mesh(12, 10, 0.0, 1);
  CHECK(mesh != NULL);
  TpPatternOptions options = tp_pattern_options_default();
  CHECK(options.courses == TP_COURSES_FREE && options.up[0] == 0.0 && options.up[2] == 1.0);
  options.time_limit_seconds = 5.0;
  TpPattern *pattern = NULL;
  CHECK(tp_pattern_solve(mesh, &options, NULL, NULL, &pattern) == TP_OK);

  TpTileOptions tile = fit_tile();
  CHECK(tile.fit == 1 && tile.fit_time_limit_seconds == 10.0 && tile.fit_overlap_tolerance < 0.0);
  CHECK(tile.fit_bond_tolerance < 0.0 && tile.units_per_mm == 0.001);

  /* Fitted (default): the report has the fit and the figures before it. */
  TpTiles *fitted = NULL;
  struct fit_progress watch = {0, 0, 0, 0, 0, 0, 0, 0.0};
  CHECK(tp_tiles_build_with_progress(mesh, pattern, NULL, &tile, watch_fit, &watch, &fitted) == TP_OK && fitted != NULL);
  CHECK(watch.calls > 0 && watch.other_stage == 0 && watch.outside == 0 && watch.backwards == 0);
  char *json = report_of(fitted);
  CHECK(json != NULL && strstr(json, "\"fit\": {") != NULL && strstr(json, "\"before_fit\"") != NULL);
  CHECK(json != NULL && strstr(json, "\"within_2mm\"") != NULL && strstr(json, "\"fit_cuts\"") != NULL);
  CHECK(json != NULL && (strstr(json, "\"status\": \"converged\"") != NULL || strstr(json, "\"status\": \"iteration_limit\"") != NULL));
  free(json);

  /* Joint deviations: one per tile, not negative, the largest is the report's worst joint. */
  size_t n = 0;
  CHECK(tp_tiles_count(fitted, &n) == TP_OK && n > 0);
  double *deviations = (double *)malloc(n * sizeof(double));
  CHECK(tp_tiles_copy_joint_deviations(fitted, deviations, n) == TP_OK);
  int finite = 1, some = 0;
  for (size_t t = 0; t < n; t++) {
    finite &= isfinite(deviations[t]) && deviations[t] >= 0.0;
    some |= deviations[t] > 0.0;
  }
  CHECK(finite && some);
  CHECK(tp_tiles_copy_joint_deviations(fitted, deviations, n - 1) == TP_BUFFER_TOO_SMALL && last_error_contains("are needed"));
  CHECK(tp_tiles_copy_joint_deviations(NULL, deviations, n) == TP_NULL_POINTER);
  CHECK(tp_tiles_copy_joint_deviations(fitted, NULL, n) == TP_NULL_POINTER);
  free(deviations);
  tp_tiles_free(fitted);

  /* fit = 0: the paper's placement, no fit in the report, no progress to report. */
  tile.fit = 0;
  TpTiles *paper = NULL;
  struct fit_progress quiet = {0, 0, 0, 0, 0, 0, 0, 0.0};
  CHECK(tp_tiles_build_with_progress(mesh, pattern, NULL, &tile, watch_fit, &quiet, &paper) == TP_OK);
  json = report_of(paper);
  CHECK(json != NULL && strstr(json, "\"fit\": {") == NULL && strstr(json, "\"before_fit\"") == NULL);
  CHECK(quiet.calls == 0);
  free(json);
  tp_tiles_free(paper);
  tile.fit = 1;

  /* Cancelled at the second report: TP_CANCELLED, no tiles, no further calls (and no leak:
     valgrind). */
  TpTiles *none = NULL;
  struct fit_progress cancel = {0, 0, 0, 0, 2, 0, 0, 0.0};
  CHECK(tp_tiles_build_with_progress(mesh, pattern, NULL, &tile, watch_fit, &cancel, &none) == TP_CANCELLED && none == NULL);
  CHECK(last_error_contains("cancelled") && cancel.cancelled && cancel.calls_after_cancel == 0 && cancel.calls == 2);
  CHECK(tp_tiles_build_with_progress(mesh, NULL, NULL, &tile, NULL, NULL, &none) == TP_NULL_POINTER && none == NULL);
  CHECK(tp_tiles_build_with_progress(mesh, pattern, NULL, &tile, NULL, NULL, NULL) == TP_NULL_POINTER);

  /* No time at all: the best placement after one step, with an honest status. */
  tile.fit_time_limit_seconds = 0.0;
  TpTiles *hurried = NULL;
  CHECK(tp_tiles_build(mesh, pattern, &tile, &hurried) == TP_OK);
  json = report_of(hurried);
  CHECK(json != NULL && strstr(json, "\"status\": \"time_limit\"") != NULL);
  free(json);
  tp_tiles_free(hurried);

  /* A caller built against the ABI 2 header: its TpTileOptions ends before `fit`. The
     initialiser writes no more than that, and the build keeps the fit on. */
  {
    unsigned char buffer[sizeof(TpTileOptions) + 16];
    memset(buffer, 0xAB, sizeof buffer);
    size_t old_size = offsetof(TpTileOptions, fit);
    CHECK(old_size == offsetof(TpTileOptions, support_band) + sizeof(double));
    CHECK(tp_tile_options_init((TpTileOptions *)(void *)buffer, old_size) == TP_OK);
    int untouched = 1;
    for (size_t b = old_size; b < sizeof buffer; b++) untouched &= buffer[b] == 0xAB;
    CHECK(untouched);
    TpTileOptions old;
    memcpy(&old, buffer, sizeof old);
    CHECK(old.struct_size == old_size);
    old.length = 1.9, old.width = 0.95, old.thickness = 0.1, old.joint = 0.1;
    old.fit = 0;                          /* beyond the old struct: never read */
    old.fit_time_limit_seconds = -1.0;    /* likewise (would be refused) */
    TpTiles *by_old = NULL;
    CHECK(tp_tiles_build(mesh, pattern, &old, &by_old) == TP_OK);
    json = report_of(by_old);
    CHECK(json != NULL && strstr(json, "\"fit\": {") != NULL && strstr(json, "\"before_fit\"") != NULL);
    free(json);
    tp_tiles_free(by_old);
  }
  tp_pattern_free(pattern);
  tp_mesh_free(mesh);
}

/* Level courses: on a grid rising along y every tile runs along x (faces f and f + 1). */
static void test_courses(void) {
  TpMesh *mesh = lifted_grid_mesh(8, 6, 0.3, 0);
  CHECK(mesh != NULL);
  TpPatternOptions options;
  CHECK(tp_pattern_options_init(&options, sizeof options) == TP_OK && options.courses == TP_COURSES_FREE);
  options.time_limit_seconds = 5.0;
  uint32_t pairs[48];
  TpPatternSummary summary;

  /* Free: tiles lie both ways. */
  TpPattern *free_pattern = NULL;
  CHECK(tp_pattern_solve(mesh, &options, NULL, NULL, &free_pattern) == TP_OK);
  CHECK(tp_pattern_summary(free_pattern, &summary) == TP_OK && summary.pairs > 0 && summary.pairs <= 24);
  CHECK(tp_pattern_copy_pairs(free_pattern, pairs, 48) == TP_OK);
  int along_x = 1;
  for (size_t k = 0; k < summary.pairs; k++) along_x &= pairs[2 * k + 1] == pairs[2 * k] + 1;
  CHECK(!along_x);
  tp_pattern_free(free_pattern);

  /* Level (up +z): every pair runs one way. */
  options.courses = TP_COURSES_LEVEL;
  TpPattern *level = NULL;
  CHECK(tp_pattern_solve(mesh, &options, NULL, NULL, &level) == TP_OK);
  CHECK(tp_pattern_summary(level, &summary) == TP_OK && summary.pairs > 0 && summary.pairs <= 24);
  CHECK(tp_pattern_copy_pairs(level, pairs, 48) == TP_OK);
  along_x = 1;
  for (size_t k = 0; k < summary.pairs; k++) along_x &= pairs[2 * k + 1] == pairs[2 * k] + 1 && pairs[2 * k] % 8 != 7;
  CHECK(along_x);
  /* Tiles on it fit (the fit keeps the pattern's bond). */
  TpTileOptions tile = fit_tile();
  TpTiles *tiles = NULL;
  CHECK(tp_tiles_build(mesh, level, &tile, &tiles) == TP_OK);
  char *json = report_of(tiles);
  CHECK(json != NULL && strstr(json, "\"fit\": {") != NULL);
  free(json);
  tp_tiles_free(tiles);
  tp_pattern_free(level);

  /* Up along x: courses along y, tiles pair f with f + 8. */
  options.up[0] = 1.0, options.up[1] = 0.0, options.up[2] = 0.0;
  CHECK(tp_pattern_solve(mesh, &options, NULL, NULL, &level) == TP_OK);
  CHECK(tp_pattern_summary(level, &summary) == TP_OK && summary.pairs > 0);
  CHECK(tp_pattern_copy_pairs(level, pairs, 48) == TP_OK);
  int along_y = 1;
  for (size_t k = 0; k < summary.pairs; k++) along_y &= pairs[2 * k + 1] == pairs[2 * k] + 8;
  CHECK(along_y);
  tp_pattern_free(level);

  /* A caller built against the ABI 2 header (struct ends before `courses`): free courses. */
  TpPatternOptions old;
  memset(&old, 0xAB, sizeof old);
  CHECK(tp_pattern_options_init(&old, offsetof(TpPatternOptions, courses)) == TP_OK);
  CHECK(old.struct_size == offsetof(TpPatternOptions, courses) && old.courses != TP_COURSES_FREE);
  old.time_limit_seconds = 5.0;
  old.courses = TP_COURSES_LEVEL; /* beyond the old struct: never read */
  TpPattern *by_old = NULL;
  CHECK(tp_pattern_solve(mesh, &old, NULL, NULL, &by_old) == TP_OK);
  CHECK(tp_pattern_summary(by_old, &summary) == TP_OK && tp_pattern_copy_pairs(by_old, pairs, 48) == TP_OK);
  along_x = 1;
  for (size_t k = 0; k < summary.pairs; k++) along_x &= pairs[2 * k + 1] == pairs[2 * k] + 1;
  CHECK(!along_x);
  tp_pattern_free(by_old);
  tp_mesh_free(mesh);
}

static void test_gap(void) {
  /* The paper's plain program on CBC would prove 10 x 10 (w = 0.5) only by branching; with a
     5 % gap it stops at the first pattern that close to its bound (ABI 4). */
  TpMesh *mesh = grid_mesh(10, 10);
  TpPatternOptions options;
  CHECK(tp_pattern_options_init(&options, sizeof options) == TP_OK && options.gap == 0.0);
  options.method = TP_METHOD_MIP;
  options.formulation = TP_FORMULATION_PAPER;
  options.time_limit_seconds = 60.0;
  options.gap = 0.05;
  TpPattern *pattern = NULL;
  TpPatternSummary summary;
  CHECK(tp_pattern_solve(mesh, &options, NULL, NULL, &pattern) == TP_OK);
  CHECK(tp_pattern_summary(pattern, &summary) == TP_OK);
  CHECK(summary.status == TP_SOLVE_FEASIBLE && summary.gap > 0.0 && summary.gap <= 0.05);
  tp_pattern_free(pattern);

  /* A caller built against the ABI 3 header (struct ends before `gap`): never read. */
  TpPatternOptions old;
  memset(&old, 0xAB, sizeof old);
  CHECK(tp_pattern_options_init(&old, offsetof(TpPatternOptions, gap)) == TP_OK);
  CHECK(old.struct_size == offsetof(TpPatternOptions, gap));
  old.time_limit_seconds = 5.0;
  old.gap = -3.0; /* beyond the old struct: an invalid gap that must not be seen */
  CHECK(tp_pattern_solve(mesh, &old, NULL, NULL, &pattern) == TP_OK);
  CHECK(tp_pattern_summary(pattern, &summary) == TP_OK && summary.status == TP_SOLVE_OPTIMAL);
  tp_pattern_free(pattern);
  tp_mesh_free(mesh);
}

/* Issue 20: the herringbone and the basket weave. An 8 x 8 basket weave is 16 squares of two
   parallel tiles, alternating: every face paired, proven; in level courses both are refused. */
static void test_bonds(void) {
  TpMesh *mesh = grid_mesh(8, 8);
  TpPatternOptions options = tp_pattern_options_default();
  options.bond = TP_BOND_BASKET_WEAVE;
  TpPattern *pattern = NULL;
  TpPatternSummary summary;
  CHECK(tp_pattern_solve(mesh, &options, NULL, NULL, &pattern) == TP_OK);
  CHECK(tp_pattern_summary(pattern, &summary) == TP_OK);
  CHECK(summary.pairs == 32 && summary.status == TP_SOLVE_OPTIMAL && summary.objective == 32.0);
  uint32_t pairs[64];
  CHECK(tp_pattern_copy_pairs(pattern, pairs, 64) == TP_OK);
  /* Each tile lies in one 2 x 2 square, along x where the square's (x + y) is even. */
  int textbook = 1, swapped = 1;
  for (int k = 0; k < 32; k++) {
    uint32_t a = pairs[2 * k], b = pairs[2 * k + 1];
    uint32_t x = a % 8, y = a / 8;
    int along_x = b == a + 1, even = ((x / 2 + y / 2) % 2) == 0;
    textbook &= along_x == even && (along_x ? x % 2 == 0 : y % 2 == 0);
    swapped &= along_x != even && (along_x ? x % 2 == 0 : y % 2 == 0);
  }
  CHECK(textbook || swapped);
  tp_pattern_free(pattern);

  options.bond = TP_BOND_HERRINGBONE;
  options.time_limit_seconds = 5.0;
  CHECK(tp_pattern_solve(mesh, &options, NULL, NULL, &pattern) == TP_OK);
  CHECK(tp_pattern_summary(pattern, &summary) == TP_OK);
  CHECK(summary.pairs > 0 && summary.bound >= summary.objective);
  tp_pattern_free(pattern);

  options.courses = TP_COURSES_LEVEL;
  pattern = NULL;
  CHECK(tp_pattern_solve(mesh, &options, NULL, NULL, &pattern) == TP_INVALID_ARGUMENT && pattern == NULL);
  CHECK(last_error_contains("herringbone") && last_error_contains("courses free"));
  options.bond = 5;
  options.courses = TP_COURSES_FREE;
  CHECK(tp_pattern_solve(mesh, &options, NULL, NULL, &pattern) == TP_INVALID_ARGUMENT);
  CHECK(last_error_contains("TP_BOND_BASKET_WEAVE"));
  tp_mesh_free(mesh);
}

/* Issue 20: zones, a bond per face (ABI 6). Zones all -1 lay every face in the options' bond:
   the same optimum as no zones; a herringbone band reaches the solve (level courses refuse it,
   free courses give a valid pattern); counts, codes and NULL are checked; a caller built
   against ABI 5 (struct ends before `zones`) never has them read. */
static void test_zones(void) {
  TpMesh *mesh = grid_mesh(8, 8);
  int32_t zones[64];
  for (int f = 0; f < 64; f++) zones[f] = TP_ZONE_DEFAULT;
  TpPatternOptions options;
  CHECK(tp_pattern_options_init(&options, sizeof options) == TP_OK);
  CHECK(options.zones == NULL && options.zone_count == 0);
  options.time_limit_seconds = 10.0;
  TpPattern *plain = NULL, *zoned = NULL;
  TpPatternSummary a, b;
  uint32_t pairs_b[64];
  CHECK(tp_pattern_solve(mesh, &options, NULL, NULL, &plain) == TP_OK);
  options.zones = zones;
  options.zone_count = 64;
  CHECK(tp_pattern_solve(mesh, &options, NULL, NULL, &zoned) == TP_OK);
  CHECK(tp_pattern_summary(plain, &a) == TP_OK && tp_pattern_summary(zoned, &b) == TP_OK);
  /* Both proven: the same optimum (the patterns themselves may differ among equal optima). */
  CHECK(a.status == TP_SOLVE_OPTIMAL && b.status == TP_SOLVE_OPTIMAL && a.objective == b.objective);
  tp_pattern_free(plain);
  tp_pattern_free(zoned);
  zoned = NULL;

  /* Rows 3 and 4 herringbone in a staggered field. */
  for (int f = 24; f < 40; f++) zones[f] = TP_BOND_HERRINGBONE;
  options.courses = TP_COURSES_LEVEL;
  CHECK(tp_pattern_solve(mesh, &options, NULL, NULL, &zoned) == TP_INVALID_ARGUMENT && zoned == NULL);
  CHECK(last_error_contains("herringbone") && last_error_contains("courses free"));
  options.courses = TP_COURSES_FREE;
  CHECK(tp_pattern_solve(mesh, &options, NULL, NULL, &zoned) == TP_OK);
  CHECK(tp_pattern_summary(zoned, &b) == TP_OK && b.faces == 64 && b.pairs > 0 && b.bound >= b.objective);
  CHECK(tp_pattern_copy_pairs(zoned, pairs_b, 64) == TP_OK);
  int adjacent = 1;
  for (size_t k = 0; k < b.pairs; k++) {
    uint32_t p = pairs_b[2 * k], q = pairs_b[2 * k + 1];
    adjacent &= (q == p + 1 && p % 8 != 7) || q == p + 8;
  }
  CHECK(adjacent);
  tp_pattern_free(zoned);
  zoned = NULL;

  /* Errors: one zone short, an unknown code (named with its index), NULL with a count. */
  options.zone_count = 63;
  CHECK(tp_pattern_solve(mesh, &options, NULL, NULL, &zoned) == TP_INVALID_ARGUMENT && zoned == NULL);
  CHECK(last_error_contains("63 bonds for a mesh of 64 faces"));
  options.zone_count = 64;
  zones[17] = 5;
  CHECK(tp_pattern_solve(mesh, &options, NULL, NULL, &zoned) == TP_INVALID_ARGUMENT && last_error_contains("zones[17] is 5"));
  zones[17] = -2;
  CHECK(tp_pattern_solve(mesh, &options, NULL, NULL, &zoned) == TP_INVALID_ARGUMENT && last_error_contains("zones[17] is -2"));
  zones[17] = TP_ZONE_DEFAULT;
  options.zones = NULL;
  CHECK(tp_pattern_solve(mesh, &options, NULL, NULL, &zoned) == TP_NULL_POINTER && last_error_contains("zones"));

  /* An ABI 5 caller: whatever lies past its struct (here a bad pointer and count) is ignored. */
  TpPatternOptions old;
  memset(&old, 0xAB, sizeof old);
  CHECK(tp_pattern_options_init(&old, offsetof(TpPatternOptions, zones)) == TP_OK);
  CHECK(old.struct_size == offsetof(TpPatternOptions, zones));
  old.time_limit_seconds = 10.0;
  old.zone_count = 3; /* beyond the old struct: never read, nor its pointer */
  CHECK(tp_pattern_solve(mesh, &old, NULL, NULL, &zoned) == TP_OK);
  CHECK(tp_pattern_summary(zoned, &b) == TP_OK && b.status == TP_SOLVE_OPTIMAL && b.objective == a.objective);
  tp_pattern_free(zoned);
  tp_mesh_free(mesh);
}

static void test_panic_boundary(void) {
#if defined(TP_TEST_PANIC)
  CHECK(tp_test_panic() == TP_PANIC);
  CHECK(last_error_contains("tp_test_panic was called"));
  /* The process lives on and the library still works. */
  TpMesh *mesh = grid_mesh(2, 2);
  CHECK(mesh != NULL);
  tp_mesh_free(mesh);
#else
  printf("panic boundary: not tested (build with the test-panic feature and -DTP_TEST_PANIC)\n");
#endif
}

/* Creases (ABI 7): a plate folded along x = 0 (the two halves turn by 44 degrees) is split
   there by default: no quad straddles the fold and tiles are cut to it; `creases` 0 runs one
   field over it; a caller built against ABI 6 gets the split. */
static size_t quads_over_the_fold(const TpMesh *quads) {
  size_t nv, nf, ni;
  CHECK(tp_mesh_counts(quads, &nv, &nf, &ni) == TP_OK);
  double *v = (double *)malloc(3 * nv * sizeof(double));
  uint32_t *idx = (uint32_t *)malloc(ni * sizeof(uint32_t)), *sz = (uint32_t *)malloc(nf * sizeof(uint32_t));
  CHECK(tp_mesh_copy_vertices(quads, v, 3 * nv) == TP_OK);
  CHECK(tp_mesh_copy_faces(quads, idx, ni, sz, nf) == TP_OK);
  size_t over = 0, at = 0;
  for (size_t f = 0; f < nf; f++) {
    int left = 0, right = 0;
    for (uint32_t k = 0; k < sz[f]; k++) {
      double x = v[3 * idx[at + k]];
      left |= x < -0.01;
      right |= x > 0.01;
    }
    over += left && right;
    at += sz[f];
  }
  free(v);
  free(idx);
  free(sz);
  return over;
}

static size_t cut_tiles(const TpMesh *quads, const TpMesh *surface, const TpTileOptions *options) {
  TpPatternOptions po;
  CHECK(tp_pattern_options_init(&po, sizeof po) == TP_OK);
  po.time_limit_seconds = 5.0;
  TpPattern *pattern = NULL;
  TpTiles *tiles = NULL;
  size_t n = 0, cut = 0;
  CHECK(tp_pattern_solve(quads, &po, NULL, NULL, &pattern) == TP_OK);
  CHECK(tp_tiles_build_on_surface(quads, pattern, surface, options, &tiles) == TP_OK);
  CHECK(tp_tiles_count(tiles, &n) == TP_OK);
  int32_t *kinds = (int32_t *)malloc(n * sizeof(int32_t));
  CHECK(tp_tiles_copy_kinds(tiles, kinds, n) == TP_OK);
  for (size_t t = 0; t < n; t++) cut += kinds[t] == TP_TILE_BOUNDARY;
  free(kinds);
  tp_tiles_free(tiles);
  tp_pattern_free(pattern);
  return cut;
}

static void test_creases(void) {
  const uint32_t nx = 24, ny = 12;
  double *v;
  uint32_t *idx, *sz;
  size_t nv, nf;
  grid(nx, ny, &v, &nv, &idx, &sz, &nf);
  for (size_t k = 0; k < nv; k++) {
    double x = 0.1 * (v[3 * k] - nx / 2.0);
    v[3 * k] = x;
    v[3 * k + 1] *= 0.1;
    v[3 * k + 2] = 0.4 * fabs(x);
  }
  TpMesh *plate = mesh_taking(v, nv, idx, 4 * nf, sz, nf);
  CHECK(plate != NULL);

  TpRemeshOptions ro;
  CHECK(tp_remesh_options_init(&ro, sizeof ro) == TP_OK);
  CHECK(ro.creases == 1);
  TpMesh *split = NULL, *joined = NULL, *old = NULL;
  CHECK(tp_remesh(plate, &ro, NULL, NULL, &split) == TP_OK);
  ro.creases = 0;
  CHECK(tp_remesh(plate, &ro, NULL, NULL, &joined) == TP_OK);
  /* An ABI 6 caller: `creases` lies past its struct, the default (on) holds. */
  ro.struct_size = (uint32_t)offsetof(TpRemeshOptions, creases);
  CHECK(tp_remesh(plate, &ro, NULL, NULL, &old) == TP_OK);
  size_t over_split = quads_over_the_fold(split), over_joined = quads_over_the_fold(joined);
  printf("creases: quads over the fold %zu split, %zu joined, %zu for an ABI 6 caller\n", over_split,
         over_joined, quads_over_the_fold(old));
  CHECK(over_split == 0 && quads_over_the_fold(old) == 0);
  CHECK(over_joined > 0);

  TpTileOptions to;
  CHECK(tp_tile_options_init(&to, sizeof to) == TP_OK);
  CHECK(to.creases == 1);
  to.fit_time_limit_seconds = 5.0;
  size_t cut_split = cut_tiles(split, plate, &to);
  to.creases = 0;
  size_t cut_joined = cut_tiles(split, plate, &to);
  to.struct_size = (uint32_t)offsetof(TpTileOptions, creases);
  size_t cut_old = cut_tiles(split, plate, &to);
  printf("creases: tiles cut %zu to the fold, %zu without it, %zu for an ABI 6 caller\n", cut_split, cut_joined,
         cut_old);
  CHECK(cut_split > cut_joined && cut_old == cut_split);
  tp_mesh_free(split);
  tp_mesh_free(joined);
  tp_mesh_free(old);
  tp_mesh_free(plate);
}

/* Renormalisation (ABI 8): on a round dome (no corner, so its field's cones are free) other
   strengths place the cones elsewhere and give other quads; a caller built against ABI 7 gets
   the default; a negative or NaN strength is refused by name. */
static int same_quads(const TpMesh *a, const TpMesh *b) {
  size_t na, fa, ia, nb, fb, ib;
  CHECK(tp_mesh_counts(a, &na, &fa, &ia) == TP_OK);
  CHECK(tp_mesh_counts(b, &nb, &fb, &ib) == TP_OK);
  if (na != nb || fa != fb || ia != ib) return 0;
  double *va = (double *)malloc(3 * na * sizeof(double)), *vb = (double *)malloc(3 * nb * sizeof(double));
  CHECK(tp_mesh_copy_vertices(a, va, 3 * na) == TP_OK);
  CHECK(tp_mesh_copy_vertices(b, vb, 3 * nb) == TP_OK);
  int same = memcmp(va, vb, 3 * na * sizeof(double)) == 0;
  free(va);
  free(vb);
  return same;
}

/* A spherical cap of radius 2 over a disk of radius 1.3, in triangles: round, so its field's
   cones are free. */
static TpMesh *round_dome(void) {
  /* A spherical cap of radius 2 over a disk of radius 1.3: a centre, 12 rings of 48. */
  enum { RINGS = 12, SECTORS = 48 };
  const double pi = 3.14159265358979323846;
  size_t nv = 1 + RINGS * SECTORS, nf = SECTORS + 2 * (RINGS - 1) * SECTORS;
  double *v = (double *)malloc(3 * nv * sizeof(double));
  uint32_t *idx = (uint32_t *)malloc(3 * nf * sizeof(uint32_t)), *sz = (uint32_t *)malloc(nf * sizeof(uint32_t));
  v[0] = 0.0;
  v[1] = 0.0;
  v[2] = 2.0;
  for (size_t i = 1; i <= RINGS; i++)
    for (size_t j = 0; j < SECTORS; j++) {
      double r = 1.3 * (double)i / RINGS, a = 2.0 * pi * (double)j / SECTORS;
      double *p = v + 3 * (1 + (i - 1) * SECTORS + j);
      p[0] = r * cos(a);
      p[1] = r * sin(a);
      p[2] = sqrt(4.0 - r * r);
    }
#define ID(i, j) ((uint32_t)((i) == 0 ? 0 : 1 + ((i) - 1) * SECTORS + ((j) % SECTORS)))
  size_t f = 0;
  for (size_t j = 0; j < SECTORS; j++) {
    uint32_t *t = idx + 3 * f++;
    t[0] = 0, t[1] = ID(1, j), t[2] = ID(1, j + 1);
  }
  for (size_t i = 1; i < RINGS; i++)
    for (size_t j = 0; j < SECTORS; j++) {
      uint32_t a = ID(i, j), b = ID(i + 1, j), c = ID(i + 1, j + 1), d = ID(i, j + 1);
      uint32_t *t = idx + 3 * f++;
      t[0] = a, t[1] = b, t[2] = c;
      t = idx + 3 * f++;
      t[0] = a, t[1] = c, t[2] = d;
    }
#undef ID
  for (size_t k = 0; k < nf; k++) sz[k] = 3;
  TpMesh *dome = mesh_taking(v, nv, idx, 3 * nf, sz, nf);
  CHECK(dome != NULL);
  return dome;
}

static void test_renormalisation(void) {
  TpMesh *dome = round_dome();
  TpRemeshOptions ro;
  CHECK(tp_remesh_options_init(&ro, sizeof ro) == TP_OK);
  CHECK(ro.renormalisation == 0.5);
  TpMesh *half = NULL, *twice = NULL, *old = NULL, *none = NULL;
  CHECK(tp_remesh(dome, &ro, NULL, NULL, &half) == TP_OK);
  ro.renormalisation = 1.0;
  CHECK(tp_remesh(dome, &ro, NULL, NULL, &twice) == TP_OK);
  ro.renormalisation = 0.0;
  CHECK(tp_remesh(dome, &ro, NULL, NULL, &none) == TP_OK);
  /* An ABI 7 caller: `renormalisation` lies past its struct, the default holds. */
  ro.struct_size = (uint32_t)offsetof(TpRemeshOptions, renormalisation);
  ro.renormalisation = 1.0;
  CHECK(tp_remesh(dome, &ro, NULL, NULL, &old) == TP_OK);
  CHECK(!same_quads(half, twice));
  CHECK(same_quads(half, old));
  ro.struct_size = sizeof ro;
  TpMesh *bad = NULL;
  ro.renormalisation = -1.0;
  CHECK(tp_remesh(dome, &ro, NULL, NULL, &bad) == TP_INVALID_ARGUMENT);
  CHECK(last_error_contains("renormalisation"));
  ro.renormalisation = NAN;
  CHECK(tp_remesh(dome, &ro, NULL, NULL, &bad) == TP_INVALID_ARGUMENT);
  CHECK(bad == NULL);
  printf("renormalisation: 0.5 and 1 give other quads, an ABI 7 caller gets 0.5, -1 and NaN refused\n");
  tp_mesh_free(half);
  tp_mesh_free(twice);
  tp_mesh_free(none);
  tp_mesh_free(old);
  tp_mesh_free(dome);
}

struct run_progress {
  int calls, other_stage, backwards, cancel_at;
  double last, cancel_from;
};

/* Cancels at the `cancel_at`-th call, or at the first fraction of at least `cancel_from`
   (when positive). */
static int32_t run_heard(void *user, uint32_t stage, double fraction) {
  struct run_progress *p = (struct run_progress *)user;
  p->calls++;
  if (stage != TP_STAGE_RUN) p->other_stage++;
  if (fraction < p->last || fraction > 1.0) p->backwards++;
  p->last = fraction;
  return (p->cancel_at > 0 && p->calls >= p->cancel_at) || (p->cancel_from > 0.0 && fraction >= p->cancel_from);
}

/* tp_run (ABI 9): one try gives the tiles of the three stages called one by one; three tries
   list every try in the report and keep one; progress is the whole run's; cancel returns
   without tiles; bad tries, quads named before they exist and a NULL out are refused. */
static void test_run(void) {
  TpMesh *dome = round_dome();
  TpRemeshOptions ro;
  TpPatternOptions po;
  TpTileOptions to;
  TpRunOptions run;
  CHECK(tp_remesh_options_init(&ro, sizeof ro) == TP_OK);
  CHECK(tp_pattern_options_init(&po, sizeof po) == TP_OK);
  CHECK(tp_tile_options_init(&to, sizeof to) == TP_OK);
  CHECK(tp_run_options_init(&run, sizeof run) == TP_OK);
  CHECK(run.tries == 0);
  po.courses = TP_COURSES_LEVEL;
  ro.target_edge = 0.15; /* as `tilepattern run` for 280 x 140 tiles in level courses */

  /* The stages one by one. */
  TpMesh *quads = NULL;
  TpPattern *pattern = NULL;
  TpTiles *tiles = NULL;
  CHECK(tp_remesh(dome, &ro, NULL, NULL, &quads) == TP_OK);
  CHECK(tp_pattern_solve(quads, &po, NULL, NULL, &pattern) == TP_OK);
  CHECK(tp_tiles_build_on_surface(quads, pattern, dome, &to, &tiles) == TP_OK);

  /* One try: the same quads and tiles. */
  run.tries = 1;
  TpMesh *run_quads = NULL;
  TpPattern *run_pattern = NULL;
  TpTiles *one = NULL;
  struct run_progress heard = {0, 0, 0, 0, 0.0, 0.0};
  CHECK(tp_run(dome, &ro, &po, &to, &run, run_heard, &heard, &run_quads, &run_pattern, &one) == TP_OK);
  CHECK(heard.calls > 0 && heard.other_stage == 0 && heard.backwards == 0);
  CHECK(same_quads(quads, run_quads));
  size_t n1 = 0, n0 = 0;
  CHECK(tp_tiles_count(tiles, &n0) == TP_OK && tp_tiles_count(one, &n1) == TP_OK);
  CHECK(n0 > 100 && n0 == n1);
  if (n0 == n1 && n0 > 0) {
    double *c0 = (double *)malloc(24 * n0 * sizeof(double)), *c1 = (double *)malloc(24 * n1 * sizeof(double));
    CHECK(tp_tiles_copy_corners(tiles, c0, 24 * n0) == TP_OK);
    CHECK(tp_tiles_copy_corners(one, c1, 24 * n1) == TP_OK);
    CHECK(memcmp(c0, c1, 24 * n0 * sizeof(double)) == 0);
    free(c0);
    free(c1);
  }
  TpPatternSummary a, b;
  CHECK(tp_pattern_summary(pattern, &a) == TP_OK && tp_pattern_summary(run_pattern, &b) == TP_OK);
  CHECK(a.pairs == b.pairs && a.objective == b.objective);

  /* Three tries: each listed, one kept, the quads and pattern handed out those of the kept. */
  run.tries = 3;
  TpMesh *best_quads = NULL;
  TpTiles *best = NULL;
  CHECK(tp_run(dome, &ro, &po, &to, &run, NULL, NULL, &best_quads, NULL, &best) == TP_OK);
  size_t needed = 0;
  CHECK(tp_tiles_report_json(best, NULL, 0, &needed) == TP_BUFFER_TOO_SMALL);
  char *json = (char *)malloc(needed + 1);
  CHECK(tp_tiles_report_json(best, json, needed + 1, NULL) == TP_OK);
  int listed = 0;
  for (const char *at = json; (at = strstr(at, "\"renormalisation\"")) != NULL; at++) listed++;
  CHECK(listed == 3);
  CHECK(strstr(json, "\"chosen_try\"") != NULL);
  const char *chosen = strstr(json, "\"chosen_try\"");
  int k = chosen != NULL ? atoi(strchr(chosen, ':') + 1) : -1;
  CHECK(k >= 0 && k < 3);
  /* The kept try's quads are the first try's exactly when the first was kept. */
  CHECK(same_quads(best_quads, quads) == (k == 0));
  printf("run: one try = the stages one by one (%zu tiles); three tries listed, try %d kept\n", n0, k);
  free(json);

  /* Cancel, early or in the last try (its fit included: a fit cancelled there would
     otherwise end the tries and hand out an earlier try's tiles): nothing handed out. */
  TpTiles *none = NULL;
  TpMesh *no_quads = NULL;
  struct run_progress stop = {0, 0, 0, 2, 0.0, 0.0};
  CHECK(tp_run(dome, &ro, &po, &to, &run, run_heard, &stop, &no_quads, NULL, &none) == TP_CANCELLED);
  CHECK(none == NULL && no_quads == NULL && last_error_contains("cancel"));
  struct run_progress late = {0, 0, 0, 0, 0.0, 0.999};
  CHECK(tp_run(dome, &ro, &po, &to, &run, run_heard, &late, &no_quads, NULL, &none) == TP_CANCELLED);
  CHECK(none == NULL && no_quads == NULL && late.last >= 0.999);

  /* A bad option of the last stage is refused before the first runs. */
  struct run_progress unheard = {0, 0, 0, 0, 0.0, 0.0};
  to.units_per_mm = 0.0;
  CHECK(tp_run(dome, &ro, &po, &to, &run, run_heard, &unheard, NULL, NULL, &none) == TP_INVALID_ARGUMENT);
  CHECK(none == NULL && unheard.calls == 0 && last_error_contains("units"));
  to.units_per_mm = 0.001;

  /* Bad input, refused by name. */
  run.tries = 7; /* one more than the six tries there are */
  CHECK(tp_run(dome, &ro, &po, &to, &run, NULL, NULL, NULL, NULL, &none) == TP_INVALID_ARGUMENT);
  CHECK(none == NULL && last_error_contains("tries"));
  run.tries = 1;
  uint32_t pair[2] = {0, 1};
  po.forced_pairs = pair;
  po.forced_pair_count = 1;
  CHECK(tp_run(dome, &ro, &po, &to, &run, NULL, NULL, NULL, NULL, &none) == TP_INVALID_ARGUMENT);
  CHECK(none == NULL && last_error_contains("forced_pair_count"));
  po.forced_pairs = NULL;
  po.forced_pair_count = 0;
  uint32_t beyond[1] = {1u << 20};
  po.excluded_faces = beyond;
  po.excluded_face_count = 1;
  CHECK(tp_run(dome, &ro, &po, &to, &run, NULL, NULL, NULL, NULL, &none) == TP_INVALID_ARGUMENT);
  CHECK(none == NULL && last_error_contains("1048576"));

  /* Excluded faces name faces of the surface: a quarter of the dome (its sectors 0-11, x
     and y > 0) left out is neither tiled nor filled. */
  uint32_t quarter[12 * 23];
  size_t nq = 0;
  for (uint32_t j = 0; j < 12; j++) {
    quarter[nq++] = j;
    for (uint32_t i = 1; i < 12; i++) {
      quarter[nq++] = 48 + 2 * ((i - 1) * 48 + j);
      quarter[nq++] = 48 + 2 * ((i - 1) * 48 + j) + 1;
    }
  }
  po.excluded_faces = quarter;
  po.excluded_face_count = nq;
  TpTiles *three_quarters = NULL;
  CHECK(tp_run(dome, &ro, &po, &to, &run, NULL, NULL, NULL, NULL, &three_quarters) == TP_OK);
  size_t n3 = 0, inside = 0;
  CHECK(tp_tiles_count(three_quarters, &n3) == TP_OK);
  CHECK(n3 > n0 / 2 && n3 < n0 * 85 / 100);
  double *c3 = (double *)malloc(24 * n3 * sizeof(double));
  CHECK(tp_tiles_copy_corners(three_quarters, c3, 24 * n3) == TP_OK);
  for (size_t t = 0; t < n3; t++) {
    double x = 0.0, y = 0.0;
    for (int c = 0; c < 8; c++) x += c3[24 * t + 3 * c] / 8.0, y += c3[24 * t + 3 * c + 1] / 8.0;
    if (x > 0.3 && y > 0.3) inside++;
  }
  CHECK(inside == 0);
  printf("run: a quarter of the dome's faces excluded: %zu tiles of %zu, none inside it\n", n3, n0);
  free(c3);
  tp_tiles_free(three_quarters);
  po.excluded_faces = NULL;
  po.excluded_face_count = 0;
  CHECK(tp_run(dome, &ro, &po, &to, &run, NULL, NULL, NULL, NULL, NULL) == TP_NULL_POINTER);
  CHECK(tp_run(NULL, &ro, &po, &to, &run, NULL, NULL, NULL, NULL, &none) == TP_NULL_POINTER);
  CHECK(tp_run(dome, &ro, &po, &to, NULL, NULL, NULL, NULL, NULL, &none) == TP_NULL_POINTER);

  tp_tiles_free(best);
  tp_mesh_free(best_quads);
  tp_tiles_free(one);
  tp_pattern_free(run_pattern);
  tp_mesh_free(run_quads);
  tp_tiles_free(tiles);
  tp_pattern_free(pattern);
  tp_mesh_free(quads);
  tp_mesh_free(dome);
}

int main(void) {
  test_version();
  test_mesh_welded();
  test_mesh();
  test_pattern_and_tiles();
  test_remesh();
  test_cancel_and_time_limit();
  test_cancel_inside_cbc();
  test_fit();
  test_courses();
  test_gap();
  test_bonds();
  test_zones();
  test_creases();
  test_renormalisation();
  test_run();
  test_panic_boundary();
  printf("%d passed, %d failed\n", passed, failed);
  return failed == 0 ? 0 : 1;
}
