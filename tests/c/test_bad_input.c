/* The C ABI's rows of the bad-input table: each bad input and the status it must return
 * (with words its message must hold); nothing may crash, leak or write outside the
 * caller's buffers (run under valgrind by `make c-test`). */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "tilepattern.h"

static int passed, failed;

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

static const double square[] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 2, 0, 0, 2, 1, 0};

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

int main(void) {
  TpMesh *m = NULL;
  const uint32_t quad[] = {0, 1, 2, 3}, four[] = {4}, two_quads[] = {0, 1, 2, 3, 1, 4, 5, 2}, fours[] = {4, 4};

  /* Meshes. */
  double nan_v[18];
  memcpy(nan_v, square, sizeof nan_v);
  nan_v[4] = NAN;
  row("NaN coordinate", mesh(nan_v, 6, quad, 4, four, 1, &m), TP_INVALID_MESH, "vertex 1");
  nan_v[4] = INFINITY;
  row("infinite coordinate", mesh(nan_v, 6, quad, 4, four, 1, &m), TP_INVALID_MESH, "vertex 1");
  const uint32_t out_of_range[] = {0, 1, 9, 3};
  row("index out of range", mesh(square, 6, out_of_range, 4, four, 1, &m), TP_INVALID_MESH, "vertex 9");
  const uint32_t repeated[] = {0, 1, 1, 3};
  row("repeated vertex", mesh(square, 6, repeated, 4, four, 1, &m), TP_INVALID_MESH, "more than once");
  const uint32_t zero[] = {0};
  row("face of size 0", mesh(square, 6, quad, 0, zero, 1, &m), TP_INVALID_MESH, "at least 3");
  const uint32_t dup[] = {0, 1, 2, 3, 1, 2, 3, 0};
  row("duplicate face", mesh(square, 6, dup, 8, fours, 2, &m), TP_INVALID_MESH, "repeats face 0");
  const uint32_t flipped[] = {0, 1, 2, 3, 2, 5, 4, 1};
  row("inconsistent orientation", mesh(square, 6, flipped, 8, fours, 2, &m), TP_INVALID_MESH, "orientations disagree");
  const uint32_t three[] = {3, 3, 3};
  const uint32_t fan[] = {0, 1, 2, 1, 0, 3, 0, 1, 4};
  row("non-manifold edge", mesh(square, 6, fan, 9, three, 3, &m), TP_INVALID_MESH, "edge 0-1");
  row("empty mesh", mesh(NULL, 0, NULL, 0, NULL, 0, &m), TP_INVALID_MESH, "empty");
  row("sizes do not add up", mesh(square, 6, quad, 3, four, 1, &m), TP_INVALID_ARGUMENT, "add up");
  row("NULL vertices", mesh(NULL, 6, quad, 4, four, 1, &m), TP_NULL_POINTER, "vertices");
  row("huge vertex count", mesh(square, SIZE_MAX, quad, 4, four, 1, &m), TP_INVALID_ARGUMENT, "vertices");
  row("huge index count", mesh(square, 6, quad, SIZE_MAX / 2, four, 1, &m), TP_INVALID_ARGUMENT, "face indices");
  row("huge face count", mesh(square, 6, quad, 4, four, (size_t)1 << 40, &m), TP_INVALID_ARGUMENT, "faces");
  row("NULL out", tp_mesh_new(square, 6, quad, 4, four, 1, NULL), TP_NULL_POINTER, "out");

  /* Options of the stages, on a valid 2-quad mesh. */
  TpMesh *quads = NULL;
  row("valid mesh", mesh(square, 6, two_quads, 8, fours, 2, &quads), TP_OK, NULL);
  TpPattern *p = NULL;
  TpPatternOptions po;
  tp_pattern_options_init(&po, sizeof po);
  po.weight = NAN;
  row("NaN weight", tp_pattern_solve(quads, &po, NULL, NULL, &p), TP_INVALID_ARGUMENT, "weight");
  tp_pattern_options_init(&po, sizeof po);
  po.time_limit_seconds = -1;
  row("negative time limit", tp_pattern_solve(quads, &po, NULL, NULL, &p), TP_INVALID_ARGUMENT, "time limit");
  po.time_limit_seconds = NAN;
  row("NaN time limit", tp_pattern_solve(quads, &po, NULL, NULL, &p), TP_INVALID_ARGUMENT, "time limit");
  tp_pattern_options_init(&po, sizeof po);
  po.bond = 99;
  row("unknown bond", tp_pattern_solve(quads, &po, NULL, NULL, &p), TP_INVALID_ARGUMENT, "bond 99");
  tp_pattern_options_init(&po, sizeof po);
  const uint32_t far_pair[] = {0, 7};
  po.forced_pairs = far_pair;
  po.forced_pair_count = 1;
  row("forced pair out of range", tp_pattern_solve(quads, &po, NULL, NULL, &p), TP_INVALID_ARGUMENT, "face 7");
  po.forced_pairs = NULL;
  row("NULL forced pairs", tp_pattern_solve(quads, &po, NULL, NULL, &p), TP_NULL_POINTER, "forced");
  tp_pattern_options_init(&po, sizeof po);
  po.struct_size = 2;
  row("struct_size too small", tp_pattern_solve(quads, &po, NULL, NULL, &p), TP_INVALID_ARGUMENT, "struct_size");
  tp_pattern_options_init(&po, sizeof po);
  po.time_limit_seconds = 0;
  row("time limit 0 (graceful: the best start)", tp_pattern_solve(quads, &po, NULL, NULL, &p), TP_OK, NULL);

  TpTiles *t = NULL;
  TpTileOptions to;
  tp_tile_options_init(&to, sizeof to);
  to.length = 0;
  row("zero tile length", tp_tiles_build(quads, p, &to, &t), TP_INVALID_ARGUMENT, "length");
  to.length = -0.3;
  row("negative tile length", tp_tiles_build(quads, p, &to, &t), TP_INVALID_ARGUMENT, "length");
  to.length = 100;
  row("tile larger than the shell", tp_tiles_build(quads, p, &to, &t), TP_INVALID_ARGUMENT, "larger than the whole mesh");
  tp_tile_options_init(&to, sizeof to);
  to.up[0] = to.up[1] = to.up[2] = 0;
  row("zero up direction", tp_tiles_build(quads, p, &to, &t), TP_INVALID_ARGUMENT, "up");
  TpMesh *other = NULL;
  row("valid single quad", mesh(square, 6, quad, 4, four, 1, &other), TP_OK, NULL);
  tp_tile_options_init(&to, sizeof to);
  to.length = 1.9;
  to.width = 0.95;
  row("pattern of another mesh", tp_tiles_build(other, p, &to, &t), TP_INVALID_PATTERN, "face 1");

  TpMesh *r = NULL;
  TpRemeshOptions ro;
  tp_remesh_options_init(&ro, sizeof ro);
  ro.target_edge = 0;
  row("zero target edge", tp_remesh(quads, &ro, NULL, NULL, &r), TP_INVALID_ARGUMENT, "target edge");
  ro.target_edge = NAN;
  row("NaN target edge", tp_remesh(quads, &ro, NULL, NULL, &r), TP_INVALID_ARGUMENT, "target edge");
  tp_remesh_options_init(&ro, sizeof ro);
  ro.direction = TP_DIRECTION_VECTOR;
  ro.direction_vector[0] = ro.direction_vector[1] = ro.direction_vector[2] = 0;
  row("zero direction vector", tp_remesh(quads, &ro, NULL, NULL, &r), TP_INVALID_ARGUMENT, "direction");

  tp_pattern_free(p);
  tp_mesh_free(quads);
  tp_mesh_free(other);
  printf("bad input: %d rows passed, %d failed\n", passed, failed);
  return failed ? 1 : 0;
}
