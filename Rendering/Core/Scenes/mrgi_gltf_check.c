#define _POSIX_C_SOURCE 200809L
#include "mrgi_gltf_check.h"

#include "mrgi_input.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

/* ---- a small JSON parser: values in one array, children linked ---------- */
enum
{
  J_NULL,
  J_FALSE,
  J_TRUE,
  J_NUMBER,
  J_STRING,
  J_ARRAY,
  J_OBJECT
};

typedef struct jvalue
{
  int32_t type;
  int32_t first; /* first child (arrays: elements; objects: keys, each followed by its value) */
  int32_t next;  /* next sibling */
  int32_t count; /* elements (arrays) or members (objects) */
  size_t start;  /* strings: offset of the first character after the quote */
  size_t length; /* strings: raw length */
  double number;
} jvalue;

typedef struct jparser
{
  const unsigned char* d;
  size_t n;
  size_t pos;
  jvalue* v;
  int32_t used;
  int32_t capacity;
  int failed;
} jparser;

static void j_ws(jparser* p)
{
  while (p->pos < p->n &&
    (p->d[p->pos] == ' ' || p->d[p->pos] == '\t' || p->d[p->pos] == '\n' || p->d[p->pos] == '\r'))
    ++p->pos;
}

static int32_t j_new(jparser* p, int32_t type)
{
  if (p->used == p->capacity)
  {
    /* At most one value per byte of input: the pool is bounded by the file. */
    int64_t cap = p->capacity ? 2 * (int64_t)p->capacity : 256;
    if (cap > (int64_t)p->n + 1)
      cap = (int64_t)p->n + 1;
    if (cap > INT32_MAX / 2 || cap <= p->used)
      return -1;
    jvalue* grown = (jvalue*)realloc(p->v, sizeof(jvalue) * (size_t)cap);
    if (!grown)
      return -1;
    p->v = grown;
    p->capacity = (int32_t)cap;
  }
  jvalue* x = &p->v[p->used];
  memset(x, 0, sizeof(*x));
  x->type = type;
  x->first = x->next = -1;
  return p->used++;
}

static int32_t j_value(jparser* p, int depth);

static int32_t j_string(jparser* p)
{
  if (p->pos >= p->n || p->d[p->pos] != '"')
    return -1;
  const size_t start = ++p->pos;
  while (p->pos < p->n && p->d[p->pos] != '"')
  {
    if (p->d[p->pos] < 0x20)
      return -1;
    if (p->d[p->pos] == '\\')
    {
      if (++p->pos >= p->n)
        return -1;
    }
    ++p->pos;
  }
  if (p->pos >= p->n)
    return -1;
  const int32_t s = j_new(p, J_STRING);
  if (s < 0)
    return -1;
  p->v[s].start = start;
  p->v[s].length = p->pos - start;
  ++p->pos;
  return s;
}

static int32_t j_value(jparser* p, int depth)
{
  if (depth > MRGI_GLTF_MAX_DEPTH)
    return -1;
  j_ws(p);
  if (p->pos >= p->n)
    return -1;
  const unsigned char c = p->d[p->pos];
  if (c == '{' || c == '[')
  {
    const int object = c == '{';
    const int32_t me = j_new(p, object ? J_OBJECT : J_ARRAY);
    if (me < 0)
      return -1;
    ++p->pos;
    j_ws(p);
    int32_t last = -1;
    if (p->pos < p->n && p->d[p->pos] == (object ? '}' : ']'))
    {
      ++p->pos;
      return me;
    }
    for (;;)
    {
      int32_t first = -1, second = -1;
      if (object)
      {
        j_ws(p);
        first = j_string(p);
        j_ws(p);
        if (first < 0 || p->pos >= p->n || p->d[p->pos] != ':')
          return -1;
        ++p->pos;
        second = j_value(p, depth + 1);
        if (second < 0)
          return -1;
        p->v[first].next = second;
      }
      else
      {
        first = second = j_value(p, depth + 1);
        if (first < 0)
          return -1;
      }
      if (last < 0)
        p->v[me].first = first;
      else
        p->v[last].next = first;
      last = second;
      ++p->v[me].count;
      j_ws(p);
      if (p->pos >= p->n)
        return -1;
      if (p->d[p->pos] == ',')
      {
        ++p->pos;
        continue;
      }
      if (p->d[p->pos] == (object ? '}' : ']'))
      {
        ++p->pos;
        return me;
      }
      return -1;
    }
  }
  if (c == '"')
    return j_string(p);
  static const char* const words[3] = { "null", "false", "true" };
  for (int w = 0; w < 3; ++w)
  {
    const size_t len = strlen(words[w]);
    if (p->n - p->pos >= len && memcmp(p->d + p->pos, words[w], len) == 0)
    {
      p->pos += len;
      return j_new(p, w);
    }
  }
  char buffer[64];
  size_t k = 0;
  while (p->pos < p->n && k + 1 < sizeof(buffer) && strchr("+-0123456789.eE", p->d[p->pos]) &&
    p->d[p->pos])
    buffer[k++] = (char)p->d[p->pos++];
  buffer[k] = '\0';
  char* end = NULL;
  const double x = strtod(buffer, &end);
  if (k == 0 || *end || !isfinite(x))
    return -1;
  const int32_t me = j_new(p, J_NUMBER);
  if (me >= 0)
    p->v[me].number = x;
  return me;
}

/* ---- access --------------------------------------------------------------- */
typedef struct gltf
{
  jparser j;
  const char* name;
  const char* base_dir;
  mrgi_error* err;
  int64_t bin_size; /* GLB BIN chunk bytes, -1 without */
  double* buffer_length;
  double* view_length;
  int32_t buffers, views, accessors, meshes, nodes, materials, textures, images, samplers, skins,
    scenes;
} gltf;

static int j_key_is(const gltf* g, int32_t key, const char* name)
{
  const jvalue* k = &g->j.v[key];
  const size_t len = strlen(name);
  return k->length == len && memcmp(g->j.d + k->start, name, len) == 0;
}

/* The member `name` of object `obj`; -1 when absent (or obj is not an object). */
static int32_t j_get(const gltf* g, int32_t obj, const char* name)
{
  if (obj < 0 || g->j.v[obj].type != J_OBJECT)
    return -1;
  for (int32_t k = g->j.v[obj].first; k >= 0; k = g->j.v[g->j.v[k].next].next)
    if (j_key_is(g, k, name))
      return g->j.v[k].next;
  return -1;
}

static int32_t j_count(const gltf* g, int32_t arr)
{
  return arr >= 0 && g->j.v[arr].type == J_ARRAY ? g->j.v[arr].count : 0;
}

static mrgi_status fail(gltf* g, const char* fmt, ...) MRGI_PRINTF_FORMAT(2, 3);
static mrgi_status fail(gltf* g, const char* fmt, ...)
{
  char text[256];
  va_list args;
  va_start(args, fmt);
  vsnprintf(text, sizeof(text), fmt, args);
  va_end(args);
  return mrgi_error_set(g->err, MRGI_ERR_FORMAT, "'%s': %s", g->name, text);
}

/* An optional integer member; `*out` = dflt when absent. 0 when present but not an integer in [lo,
 * hi]. */
static int j_int(
  const gltf* g, int32_t obj, const char* name, double lo, double hi, double dflt, double* out)
{
  const int32_t x = j_get(g, obj, name);
  if (x < 0)
  {
    *out = dflt;
    return 1;
  }
  const jvalue* v = &g->j.v[x];
  if (v->type != J_NUMBER || v->number != floor(v->number) || v->number < lo || v->number > hi)
    return 0;
  *out = v->number;
  return 1;
}

/* A reference member: absent is fine unless `required`; else an index in [0, limit). */
static mrgi_status j_ref(gltf* g, int32_t obj, const char* member, int32_t limit, int required,
  const char* what, long long i)
{
  double v = 0;
  const int32_t x = j_get(g, obj, member);
  if (x < 0)
    return required ? fail(g, "%s %lld has no '%s'", what, (long long)i, member) : MRGI_OK;
  if (!j_int(g, obj, member, 0, (double)limit - 1, 0, &v) || limit == 0)
  {
    return mrgi_error_set(g->err, MRGI_ERR_FORMAT, "'%s': %s %lld: '%s' is not an index below %d",
      g->name, what, i, member, (int)limit);
  }
  return MRGI_OK;
}

/* Whether a URI names a readable regular file next to the document (or a data URI); its size in
 * *size. */
static mrgi_status uri_size(gltf* g, int32_t uri, const char* what, long long i, double* size)
{
  const jvalue* u = &g->j.v[uri];
  if (u->type != J_STRING)
    return fail(g, "%s %lld: 'uri' is not a string", what, (long long)i);
  const char* s = (const char*)g->j.d + u->start;
  if (u->length >= 5 && memcmp(s, "data:", 5) == 0)
  {
    const char* comma = memchr(s, ',', u->length);
    if (!comma || (size_t)(comma - s) < 7 || memcmp(comma - 7, ";base64", 7) != 0)
      return fail(g, "%s %lld: a data URI that is not base64", what, (long long)i);
    const size_t n = u->length - (size_t)(comma + 1 - s);
    size_t pad = 0;
    for (size_t k = 0; k < n; ++k)
    {
      const char c = comma[1 + k];
      const int ok = (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') ||
        c == '+' || c == '/' || (c == '=' && k + 2 >= n);
      if (!ok)
        return fail(g, "%s %lld: bad base64 in its data URI (at character %lld)", what,
          (long long)i, (long long)k);
      pad += c == '=';
    }
    if (n % 4)
      return fail(g, "%s %lld: a base64 data URI whose length (%lld) is not a multiple of 4", what,
        (long long)i, (long long)n);
    *size = (double)(n / 4 * 3 - pad);
    return MRGI_OK;
  }
  if (!g->base_dir)
    return fail(g, "%s %lld: external URIs are not read here", what, (long long)i);
  if (u->length == 0 || u->length > 1024 || memchr(s, '\\', u->length))
    return fail(g, "%s %lld: a URI that is empty, too long or escaped", what, (long long)i);
  char path[2200];
  if (s[0] == '/')
    snprintf(path, sizeof(path), "%.*s", (int)u->length, s);
  else
    snprintf(path, sizeof(path), "%s/%.*s", g->base_dir, (int)u->length, s);
  mrgi_error inner;
  if (mrgi_input_check_regular(path, &inner) != MRGI_OK)
    return mrgi_error_set(
      g->err, MRGI_ERR_FORMAT, "'%s': %s %lld: %s", g->name, what, i, inner.message);
  struct stat st;
  if (stat(path, &st) != 0)
    return fail(g, "%s %lld: its URI cannot be read", what, (long long)i);
  *size = (double)st.st_size;
  return MRGI_OK;
}

static int component_size(double t)
{
  return t == 5120 || t == 5121 ? 1 : t == 5122 || t == 5123 ? 2 : t == 5125 || t == 5126 ? 4 : 0;
}

static int type_components(const gltf* g, int32_t t)
{
  static const struct
  {
    const char* name;
    int n;
  } types[] = { { "SCALAR", 1 }, { "VEC2", 2 }, { "VEC3", 3 }, { "VEC4", 4 }, { "MAT2", 4 },
    { "MAT3", 9 }, { "MAT4", 16 } };
  if (t < 0 || g->j.v[t].type != J_STRING)
    return 0;
  for (size_t k = 0; k < sizeof(types) / sizeof(types[0]); ++k)
    if (j_key_is(g, t, types[k].name))
      return types[k].n;
  return 0;
}

/* A range of `bytes` at `offset` within bufferView `view`. */
static mrgi_status view_range(gltf* g, int32_t obj, const char* member, double offset, double bytes,
  const char* what, long long i)
{
  mrgi_status s = j_ref(g, obj, member, g->views, 1, what, i);
  if (s)
    return s;
  double view = 0;
  j_int(g, obj, member, 0, 1e18, 0, &view);
  if (offset + bytes > g->view_length[(int32_t)view])
    return fail(g, "%s %lld needs %lld bytes more than its bufferView holds", what, (long long)i,
      (long long)(offset + bytes - g->view_length[(int32_t)view]));
  return MRGI_OK;
}

static mrgi_status check_document(gltf* g, int32_t root)
{
  mrgi_status s = MRGI_OK;
  if (root < 0 || g->j.v[root].type != J_OBJECT)
    return mrgi_error_set(
      g->err, MRGI_ERR_FORMAT, "'%s': the glTF document is not a JSON object", g->name);
  const int32_t buffers = j_get(g, root, "buffers"), views = j_get(g, root, "bufferViews");
  const int32_t accessors = j_get(g, root, "accessors"), meshes = j_get(g, root, "meshes");
  const int32_t nodes = j_get(g, root, "nodes"), scenes = j_get(g, root, "scenes");
  const int32_t images = j_get(g, root, "images"), textures = j_get(g, root, "textures");
  const int32_t materials = j_get(g, root, "materials"), skins = j_get(g, root, "skins");
  const int32_t animations = j_get(g, root, "animations"), samplers = j_get(g, root, "samplers");
  const char* const arrays[] = { "buffers", "bufferViews", "accessors", "meshes", "nodes", "scenes",
    "images", "textures", "materials", "skins", "animations", "samplers", "cameras" };
  for (size_t k = 0; k < sizeof(arrays) / sizeof(arrays[0]); ++k)
  {
    const int32_t a = j_get(g, root, arrays[k]);
    if (a >= 0 && g->j.v[a].type != J_ARRAY)
      return fail(g, "'%s' is not an array", arrays[k]);
    long long i = 0;
    for (int32_t e = a >= 0 ? g->j.v[a].first : -1; e >= 0; e = g->j.v[e].next, ++i)
      if (g->j.v[e].type != J_OBJECT)
        return fail(g, "%s %lld is not an object", arrays[k], (long long)i);
  }
  g->buffers = j_count(g, buffers);
  g->views = j_count(g, views);
  g->accessors = j_count(g, accessors);
  g->meshes = j_count(g, meshes);
  g->nodes = j_count(g, nodes);
  g->scenes = j_count(g, scenes);
  g->images = j_count(g, images);
  g->textures = j_count(g, textures);
  g->materials = j_count(g, materials);
  g->skins = j_count(g, skins);
  g->samplers = j_count(g, samplers);
  if (g->meshes == 0)
    return mrgi_error_set(g->err, MRGI_ERR_FORMAT, "'%s': the glTF file holds no meshes", g->name);

  g->buffer_length = (double*)calloc((size_t)g->buffers + 1, sizeof(double));
  g->view_length = (double*)calloc((size_t)g->views + 1, sizeof(double));
  if (!g->buffer_length || !g->view_length)
    return mrgi_error_set(g->err, MRGI_ERR_OUT_OF_MEMORY, "'%s': out of memory", g->name);
  long long i = 0;
  for (int32_t b = j_count(g, buffers) ? g->j.v[buffers].first : -1; b >= 0;
       b = g->j.v[b].next, ++i)
  {
    double length = 0, have = 0;
    if (!j_int(g, b, "byteLength", 1, 1e18, -1, &length) || length < 1)
      return fail(g, "buffer %lld: byteLength is not a positive integer", (long long)i);
    const int32_t uri = j_get(g, b, "uri");
    if (uri >= 0)
    {
      if ((s = uri_size(g, uri, "buffer", i, &have)))
        return s;
    }
    else if (i == 0 && g->bin_size >= 0)
      have = (double)g->bin_size;
    else
      return fail(g, "buffer %lld has no 'uri' (and no GLB binary chunk)", (long long)i);
    if (have < length)
      return fail(g, "buffer %lld: byteLength %lld is more than its data hold", (long long)i,
        (long long)length);
    g->buffer_length[(int32_t)i] = length;
  }
  i = 0;
  for (int32_t v = j_count(g, views) ? g->j.v[views].first : -1; v >= 0; v = g->j.v[v].next, ++i)
  {
    double buffer = 0, offset = 0, length = 0, stride = 0;
    if ((s = j_ref(g, v, "buffer", g->buffers, 1, "bufferView", i)))
      return s;
    j_int(g, v, "buffer", 0, 1e18, 0, &buffer);
    if (!j_int(g, v, "byteOffset", 0, 1e18, 0, &offset) ||
      !j_int(g, v, "byteLength", 1, 1e18, -1, &length) || length < 1 ||
      !j_int(g, v, "byteStride", 4, 252, 0, &stride))
      return fail(
        g, "bufferView %lld: byteOffset, byteLength or byteStride is not valid", (long long)i);
    if (offset + length > g->buffer_length[(int32_t)buffer])
      return fail(g, "bufferView %lld reaches beyond its buffer (byte %lld)", (long long)i,
        (long long)(offset + length));
    g->view_length[(int32_t)i] = length;
  }
  i = 0;
  for (int32_t a = j_count(g, accessors) ? g->j.v[accessors].first : -1; a >= 0;
       a = g->j.v[a].next, ++i)
  {
    double ctype = 0, count = 0, offset = 0;
    if (!j_int(g, a, "componentType", 0, 1e9, -1, &ctype) || component_size(ctype) == 0)
      return fail(g, "accessor %lld: unknown componentType", (long long)i);
    const int comps = type_components(g, j_get(g, a, "type"));
    if (comps == 0)
      return fail(g, "accessor %lld: unknown type", (long long)i);
    if (!j_int(g, a, "count", 1, 1e15, -1, &count) || count < 1)
      return fail(g, "accessor %lld: count is not a positive integer", (long long)i);
    if (!j_int(g, a, "byteOffset", 0, 1e18, 0, &offset))
      return fail(g, "accessor %lld: bad byteOffset", (long long)i);
    const double element = (double)(component_size(ctype) * comps);
    if (j_get(g, a, "bufferView") >= 0)
    {
      double view = 0, stride = 0;
      if ((s = j_ref(g, a, "bufferView", g->views, 1, "accessor", i)))
        return s;
      j_int(g, a, "bufferView", 0, 1e18, 0, &view);
      /* The view's stride, when it has one. */
      int32_t vv = g->j.v[views].first;
      for (int32_t k = 0; k < (int32_t)view; ++k)
        vv = g->j.v[vv].next;
      j_int(g, vv, "byteStride", 4, 252, element, &stride);
      if (offset + (count - 1) * stride + element > g->view_length[(int32_t)view])
        return fail(g, "accessor %lld: %lld elements do not fit in its bufferView", (long long)i,
          (long long)count);
    }
    else if (count * element > (double)(1 << 28))
      return fail(g, "accessor %lld: %lld elements without data", (long long)i, (long long)count);
    const int32_t sparse = j_get(g, a, "sparse");
    if (sparse >= 0)
    {
      double scount = 0, soff = 0, sctype = 0;
      const int32_t idx = j_get(g, sparse, "indices"), val = j_get(g, sparse, "values");
      if (!j_int(g, sparse, "count", 1, count, -1, &scount) || scount < 1 || idx < 0 || val < 0)
        return fail(g, "accessor %lld: bad sparse part", (long long)i);
      if (!j_int(g, idx, "componentType", 0, 1e9, -1, &sctype) || component_size(sctype) == 0 ||
        !j_int(g, idx, "byteOffset", 0, 1e18, 0, &soff))
        return fail(g, "accessor %lld: bad sparse indices", (long long)i);
      if ((s = view_range(g, idx, "bufferView", soff, scount * component_size(sctype),
             "sparse indices of accessor", i)))
        return s;
      if (!j_int(g, val, "byteOffset", 0, 1e18, 0, &soff))
        return fail(g, "accessor %lld: bad sparse values", (long long)i);
      if ((s = view_range(
             g, val, "bufferView", soff, scount * element, "sparse values of accessor", i)))
        return s;
    }
  }
  i = 0;
  for (int32_t m = g->j.v[meshes].first; m >= 0; m = g->j.v[m].next, ++i)
  {
    const int32_t prims = j_get(g, m, "primitives");
    if (j_count(g, prims) == 0)
      return fail(g, "mesh %lld has no primitives", (long long)i);
    for (int32_t p = g->j.v[prims].first; p >= 0; p = g->j.v[p].next)
    {
      if (g->j.v[p].type != J_OBJECT)
        return fail(g, "mesh %lld: a primitive is not an object", (long long)i);
      const int32_t attributes = j_get(g, p, "attributes");
      if (attributes < 0 || g->j.v[attributes].type != J_OBJECT ||
        j_get(g, attributes, "POSITION") < 0)
        return fail(g, "mesh %lld: a primitive without a POSITION attribute", (long long)i);
      for (int32_t k = g->j.v[attributes].first; k >= 0; k = g->j.v[g->j.v[k].next].next)
      {
        const jvalue* x = &g->j.v[g->j.v[k].next];
        if (x->type != J_NUMBER || x->number != floor(x->number) || x->number < 0 ||
          x->number >= g->accessors)
          return fail(g, "mesh %lld: an attribute names accessor %lld, which does not exist",
            (long long)i,
            (long long)(x->type == J_NUMBER && fabs(x->number) < 9e18 ? (long long)x->number : -1));
      }
      if ((s = j_ref(g, p, "indices", g->accessors, 0, "mesh", i)) ||
        (s = j_ref(g, p, "material", g->materials, 0, "mesh", i)))
        return s;
      const int32_t targets = j_get(g, p, "targets");
      for (int32_t t = j_count(g, targets) ? g->j.v[targets].first : -1; t >= 0; t = g->j.v[t].next)
        for (int32_t k = g->j.v[t].type == J_OBJECT ? g->j.v[t].first : -1; k >= 0;
             k = g->j.v[g->j.v[k].next].next)
        {
          const jvalue* x = &g->j.v[g->j.v[k].next];
          if (x->type != J_NUMBER || x->number < 0 || x->number >= g->accessors ||
            x->number != floor(x->number))
            return fail(
              g, "mesh %lld: a morph target names an accessor that does not exist", (long long)i);
        }
    }
  }
  /* Nodes: references, then no cycle (iterative depth-first search). */
  int32_t* node_value = (int32_t*)calloc((size_t)g->nodes + 1, sizeof(int32_t));
  unsigned char* state = (unsigned char*)calloc((size_t)g->nodes + 1, 1);
  int32_t* stack = (int32_t*)calloc((size_t)g->nodes + 1, sizeof(int32_t));
  int32_t* cursor = (int32_t*)calloc((size_t)g->nodes + 1, sizeof(int32_t));
  if (!node_value || !state || !stack || !cursor)
    s = mrgi_error_set(g->err, MRGI_ERR_OUT_OF_MEMORY, "'%s': out of memory", g->name);
  i = 0;
  for (int32_t n = g->nodes ? g->j.v[nodes].first : -1; n >= 0 && !s; n = g->j.v[n].next, ++i)
  {
    node_value[(int32_t)i] = n;
    if ((s = j_ref(g, n, "mesh", g->meshes, 0, "node", i)) ||
      (s = j_ref(g, n, "skin", g->skins, 0, "node", i)) ||
      (s = j_ref(g, n, "camera", j_count(g, j_get(g, root, "cameras")), 0, "node", i)))
      break;
    const int32_t children = j_get(g, n, "children");
    if (children >= 0 && g->j.v[children].type != J_ARRAY)
      s = fail(g, "node %lld: 'children' is not an array", (long long)i);
    for (int32_t c = children >= 0 ? g->j.v[children].first : -1; c >= 0 && !s; c = g->j.v[c].next)
    {
      const jvalue* x = &g->j.v[c];
      if (x->type != J_NUMBER || x->number < 0 || x->number >= g->nodes ||
        x->number != floor(x->number))
        s = fail(g, "node %lld has a child that does not exist (%g)", (long long)i,
          /* %g: a JSON number may lie far outside long long (fuzzing: 1e36) */
          x->type == J_NUMBER ? x->number : -1.0);
    }
  }
  for (int32_t start = 0; start < g->nodes && !s; ++start)
  {
    if (state[start])
      continue;
    int32_t top = 0;
    stack[0] = start;
    state[start] = 1;
    const int32_t ch0 = j_get(g, node_value[start], "children");
    cursor[0] = ch0 >= 0 ? g->j.v[ch0].first : -1;
    while (top >= 0 && !s)
    {
      const int32_t c = cursor[top];
      if (c < 0)
      {
        state[stack[top]] = 2;
        --top;
        continue;
      }
      cursor[top] = g->j.v[c].next;
      const int32_t child = (int32_t)g->j.v[c].number;
      if (state[child] == 1)
        s = fail(g, "the node graph has a cycle (node %lld is its own ancestor, through node %lld)",
          (long long)child, (long long)stack[top]);
      else if (state[child] == 0)
      {
        state[child] = 1;
        stack[++top] = child;
        const int32_t ch = j_get(g, node_value[child], "children");
        cursor[top] = ch >= 0 ? g->j.v[ch].first : -1;
      }
    }
  }
  free(node_value);
  free(state);
  free(stack);
  free(cursor);
  if (s)
    return s;
  if ((s = j_ref(g, root, "scene", g->scenes, 0, "the document", 0)))
    return s;
  i = 0;
  for (int32_t sc = g->scenes ? g->j.v[scenes].first : -1; sc >= 0; sc = g->j.v[sc].next, ++i)
  {
    const int32_t list = j_get(g, sc, "nodes");
    for (int32_t c = j_count(g, list) ? g->j.v[list].first : -1; c >= 0; c = g->j.v[c].next)
    {
      const jvalue* x = &g->j.v[c];
      if (x->type != J_NUMBER || x->number < 0 || x->number >= g->nodes ||
        x->number != floor(x->number))
        return fail(g, "scene %lld names a node that does not exist (%g)", (long long)i,
          /* %g: a JSON number may lie far outside long long (fuzzing: 1e36) */
          x->type == J_NUMBER ? x->number : -1.0);
    }
  }
  i = 0;
  for (int32_t t = g->textures ? g->j.v[textures].first : -1; t >= 0; t = g->j.v[t].next, ++i)
    if ((s = j_ref(g, t, "source", g->images, 0, "texture", i)) ||
      (s = j_ref(g, t, "sampler", g->samplers, 0, "texture", i)))
      return s;
  i = 0;
  for (int32_t im = g->images ? g->j.v[images].first : -1; im >= 0; im = g->j.v[im].next, ++i)
  {
    const int32_t uri = j_get(g, im, "uri");
    double size = 0;
    if (uri >= 0)
    {
      if ((s = uri_size(g, uri, "image", i, &size)))
        return s;
    }
    else if ((s = j_ref(g, im, "bufferView", g->views, 1, "image", i)))
      return s;
  }
  i = 0;
  for (int32_t m = g->materials ? g->j.v[materials].first : -1; m >= 0; m = g->j.v[m].next, ++i)
  {
    const int32_t pbr = j_get(g, m, "pbrMetallicRoughness");
    const int32_t refs[5] = { j_get(g, pbr, "baseColorTexture"),
      j_get(g, pbr, "metallicRoughnessTexture"), j_get(g, m, "normalTexture"),
      j_get(g, m, "occlusionTexture"), j_get(g, m, "emissiveTexture") };
    for (int k = 0; k < 5; ++k)
      if (refs[k] >= 0 && (s = j_ref(g, refs[k], "index", g->textures, 1, "material", i)))
        return s;
  }
  i = 0;
  for (int32_t sk = g->skins ? g->j.v[skins].first : -1; sk >= 0; sk = g->j.v[sk].next, ++i)
  {
    if ((s = j_ref(g, sk, "inverseBindMatrices", g->accessors, 0, "skin", i)) ||
      (s = j_ref(g, sk, "skeleton", g->nodes, 0, "skin", i)))
      return s;
    const int32_t joints = j_get(g, sk, "joints");
    if (j_count(g, joints) == 0)
      return fail(g, "skin %lld has no joints", (long long)i);
    for (int32_t c = g->j.v[joints].first; c >= 0; c = g->j.v[c].next)
    {
      const jvalue* x = &g->j.v[c];
      if (x->type != J_NUMBER || x->number < 0 || x->number >= g->nodes ||
        x->number != floor(x->number))
        return fail(g, "skin %lld names a joint that does not exist (%g)", (long long)i,
          /* %g: a JSON number may lie far outside long long (fuzzing: 1e36) */
          x->type == J_NUMBER ? x->number : -1.0);
    }
  }
  i = 0;
  for (int32_t an = j_count(g, animations) ? g->j.v[animations].first : -1; an >= 0;
       an = g->j.v[an].next, ++i)
  {
    const int32_t smp = j_get(g, an, "samplers"), channels = j_get(g, an, "channels");
    const int32_t nsamplers = j_count(g, smp);
    for (int32_t x = nsamplers ? g->j.v[smp].first : -1; x >= 0; x = g->j.v[x].next)
      if ((s = j_ref(g, x, "input", g->accessors, 1, "animation", i)) ||
        (s = j_ref(g, x, "output", g->accessors, 1, "animation", i)))
        return s;
    for (int32_t x = j_count(g, channels) ? g->j.v[channels].first : -1; x >= 0; x = g->j.v[x].next)
    {
      if ((s = j_ref(g, x, "sampler", nsamplers, 1, "animation", i)))
        return s;
      const int32_t target = j_get(g, x, "target");
      if (target < 0 || (s = j_ref(g, target, "node", g->nodes, 0, "animation", i)))
        return s ? s : fail(g, "animation %lld: a channel without target", (long long)i);
    }
  }
  return MRGI_OK;
}

static uint32_t le32(const unsigned char* p)
{
  return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

mrgi_status mrgi_gltf_check_buffer(const void* data, size_t size, const char* name,
  const char* base_dir, mrgi_gltf_info* info, mrgi_error* err)
{
  gltf g;
  memset(&g, 0, sizeof(g));
  g.name = name ? name : "glTF data";
  g.base_dir = base_dir;
  g.err = err;
  g.bin_size = -1;
  const unsigned char* d = (const unsigned char*)data;
  if (!d || size == 0)
    return mrgi_error_set(err, MRGI_ERR_FORMAT, "'%s' is empty", g.name);
  const unsigned char* json = d;
  size_t json_size = size;
  const int binary = size >= 4 && memcmp(d, "glTF", 4) == 0;
  if (binary)
  {
    if (size < 20 || le32(d + 4) != 2)
      return mrgi_error_set(
        err, MRGI_ERR_FORMAT, "'%s': not a version 2 GLB file (or truncated)", g.name);
    const uint32_t total = le32(d + 8);
    if (total > size || total < 20)
      return mrgi_error_set(err, MRGI_ERR_FORMAT,
        "'%s': the GLB header declares %u bytes, the file has %llu", g.name, total,
        (unsigned long long)size);
    const uint32_t jlen = le32(d + 12);
    if (le32(d + 16) != 0x4E4F534Au || jlen > total - 20)
      return mrgi_error_set(err, MRGI_ERR_FORMAT,
        "'%s': the GLB JSON chunk is missing or longer than the file", g.name);
    json = d + 20;
    json_size = jlen;
    const size_t next = 20 + (size_t)jlen;
    if (total - next >= 8)
    {
      const uint32_t blen = le32(d + next);
      if (le32(d + next + 4) == 0x004E4942u)
      {
        if (blen > total - next - 8)
          return mrgi_error_set(
            err, MRGI_ERR_FORMAT, "'%s': the GLB binary chunk is longer than the file", g.name);
        g.bin_size = blen;
      }
    }
  }
  g.j.d = json;
  g.j.n = json_size;
  const int32_t root = j_value(&g.j, 0);
  j_ws(&g.j);
  mrgi_status s = MRGI_OK;
  if (root < 0 || g.j.pos != g.j.n)
  {
    /* GLB JSON chunks may end in spaces (checked by j_ws) or NULs in bad writers. */
    s = mrgi_error_set(err, MRGI_ERR_FORMAT,
      "'%s': the glTF JSON is not valid (near byte %llu; nesting is limited to %d levels)", g.name,
      (unsigned long long)g.j.pos, MRGI_GLTF_MAX_DEPTH);
  }
  else
    s = check_document(&g, root);
  if (s == MRGI_OK && info)
  {
    info->mesh_count = g.meshes;
    info->node_count = g.nodes;
    info->accessor_count = g.accessors;
    info->binary = binary;
  }
  free(g.j.v);
  free(g.buffer_length);
  free(g.view_length);
  return s;
}

mrgi_status mrgi_gltf_check(const char* path, mrgi_gltf_info* info, mrgi_error* err)
{
  mrgi_input in;
  mrgi_status status = mrgi_input_map(path, &in, err);
  if (status != MRGI_OK)
    return status;
  char dir[1024];
  const char* slash = strrchr(path, '/');
  if (!slash)
    snprintf(dir, sizeof(dir), ".");
  else
    snprintf(dir, sizeof(dir), "%.*s", (int)(slash == path ? 1 : slash - path), path);
  status = mrgi_gltf_check_buffer(in.data, in.size, path, dir, info, err);
  mrgi_input_unmap(&in);
  return status;
}
