/* mrgi_input, mrgi_obj_check, mrgi_vtk_check, mrgi_gltf_check, mrgi_xml_check and the PLY
 * buffer check: sound data pass; each crash class of MRGI issue 18 is
 * refused with a message naming the problem; non-regular files are refused
 * before anything is read. */
#define _POSIX_C_SOURCE 200809L
#include "mrgi_gltf_check.h"
#include "mrgi_input.h"
#include "mrgi_obj_check.h"
#include "mrgi_ply_check.h"
#include "mrgi_test.h"
#include "mrgi_vtk_check.h"
#include "mrgi_xml_check.h"

#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

typedef mrgi_status (*check_fn)(const char* text, mrgi_error* err);

static mrgi_status obj(const char* t, mrgi_error* e)
{
  return mrgi_obj_check_buffer(t, strlen(t), "t.obj", NULL, e);
}
static mrgi_status vtk(const char* t, mrgi_error* e)
{
  return mrgi_vtk_check_buffer(t, strlen(t), "t.vtk", NULL, e);
}
static mrgi_status ply(const char* t, mrgi_error* e)
{
  return mrgi_ply_check_buffer(t, strlen(t), "t.ply", NULL, e);
}
static mrgi_status gltf(const char* t, mrgi_error* e)
{
  return mrgi_gltf_check_buffer(t, strlen(t), "t.gltf", NULL, NULL, e);
}

/* "HHHH" in the text stands for a raw UInt32 little-endian block header of 12 bytes (it holds
 * NULs). */
static mrgi_status xml(const char* t, mrgi_error* e)
{
  char copy[1024];
  const size_t n = strlen(t);
  memcpy(copy, t, n + 1);
  char* h = strstr(copy, "HHHH");
  if (h)
    memcpy(h, "\014\0\0\0", 4);
  return mrgi_xml_check_buffer(copy, n, "t.vtp", e);
}

static void expect(check_fn f, const char* text, const char* fragment)
{
  mrgi_error err;
  err.message[0] = '\0';
  const mrgi_status s = f(text, &err);
  if (!fragment)
  {
    if (s != MRGI_OK)
      MRGI_FAIL("refused: %s", err.message);
    return;
  }
  if (s != MRGI_ERR_FORMAT || !strstr(err.message, fragment))
    MRGI_FAIL("status %d, message '%s' lacks '%s'", (int)s, err.message, fragment);
}

static void test_obj(void)
{
  const char* v = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  char t[256];
  expect(obj, v, NULL);
  snprintf(t, sizeof(t), "%sf 1 2 3\nf -3 -2 -1\nf 1/1 2/1 3/1\nvt 0 0\n", v);
  expect(obj, t, NULL);
  snprintf(t, sizeof(t), "%sf 1 2 4\n", v);
  expect(obj, t, "out of range");
  snprintf(t, sizeof(t), "%sf 0 1 2\n", v);
  expect(obj, t, "index 0 out of range");
  snprintf(t, sizeof(t), "%sf 1 2 -4\n", v);
  expect(obj, t, "out of range");
  snprintf(t, sizeof(t), "%sf 1//1 2//1 3//1\n", v);
  expect(obj, t, "normal index");
  snprintf(t, sizeof(t), "%sf 1 2\n", v);
  expect(obj, t, "at least 3");
  snprintf(t, sizeof(t), "%sf 1 2 99999999999999999999\n", v);
  expect(obj, t, "bad index");
  expect(obj, "v 1 2\n", "3 numbers");
  expect(obj, "# nothing\n", "no vertices");
}

static void test_vtk(void)
{
  const char* h =
    "# vtk DataFile Version 3.0\nt\nASCII\nDATASET POLYDATA\nPOINTS 3 float\n0 0 0 1 0 0 0 1 0\n";
  char t[512];
  snprintf(t, sizeof(t),
    "%sPOLYGONS 1 4\n3 0 1 2\nPOINT_DATA 3\nSCALARS s float\nLOOKUP_TABLE default\n1 2 3\n", h);
  expect(vtk, t, NULL);
  snprintf(t, sizeof(t), "%sPOLYGONS 1 4\n3 0 1 3\n", h);
  expect(vtk, t, "outside [0, 3)");
  snprintf(t, sizeof(t), "%sPOLYGONS 1 3\n3 0 1 2\n", h);
  expect(vtk, t, "does not fit");
  snprintf(t, sizeof(t), "%sPOLYGONS 2000000000 2000000000\n3 0 1 2\n", h);
  expect(vtk, t, "more than the file holds");
  snprintf(t, sizeof(t), "%sPOLYGONS 1 4\n3 0 1 2\nPOINT_DATA 7\n", h);
  expect(vtk, t, "POINT_DATA 7");
  expect(vtk,
    "# vtk DataFile Version 3.0\nt\nASCII\nDATASET POLYDATA\nPOINTS 2000000000 float\n0 0 0\n",
    "POINTS declares");
  expect(vtk,
    "# vtk DataFile Version 3.0\nt\nASCII\nDATASET STRUCTURED_POINTS\nDIMENSIONS 100000 100000 "
    "100000\n",
    "too large");
  expect(vtk,
    "# vtk DataFile Version 3.0\nt\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 3 float\n0 0 0 1 0 0 "
    "0 1 0\n"
    "CELLS 1 4\n3 0 1 2\nCELL_TYPES 1\n12\n",
    "needs 8");
  expect(vtk,
    "# vtk DataFile Version 5.1\nt\nASCII\nDATASET POLYDATA\nPOINTS 3 float\n0 0 0 1 0 0 0 1 0\n"
    "POLYGONS 2 3\nOFFSETS vtktypeint64\n0 300\nCONNECTIVITY vtktypeint64\n0 1 2\n",
    "offsets must");
  expect(vtk, "not vtk\n", "not a legacy VTK file");
}

static void test_ply(void)
{
  const char* h =
    "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float "
    "z\n"
    "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n";
  char t[512];
  snprintf(t, sizeof(t), "%s3 0 1 2\n", h);
  expect(ply, t, NULL);
  snprintf(t, sizeof(t), "%s3 0 1 3\n", h);
  expect(ply, t, "outside [0, 3)");
  snprintf(t, sizeof(t), "%s3 0 -1 2\n", h);
  expect(ply, t, "outside [0, 3)");
  snprintf(t, sizeof(t), "%s9 0 1 2\n", h);
  expect(ply, t, "fewer list items");
  expect(ply,
    "ply\nformat ascii 1.0\ncomment xxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxx",
    "end_header");
}

static void test_gltf(void)
{
  /* One triangle: 3 float positions (36 bytes) as a base64 data URI. */
  static const char* const ok =
    "{\"asset\":{\"version\":\"2.0\"},\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0}"
    "}]}],"
    "\"nodes\":[{\"mesh\":0%s}],%s\"buffers\":[{\"byteLength\":36,\"uri\":\"data:application/"
    "octet-stream;base64,"
    "AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA\"}],\"bufferViews\":[{\"buffer\":0,"
    "\"byteLength\":36}],"
    "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":%s,\"type\":\"VEC3\"}]}";
  char t[1024];
  snprintf(t, sizeof(t), ok, "", "", "3");
  expect(gltf, t, NULL);
  snprintf(t, sizeof(t), ok, "", "", "4");
  expect(gltf, t, "do not fit");
  snprintf(t, sizeof(t), ok, ",\"children\":[0]", "", "3");
  expect(gltf, t, "cycle");
  snprintf(t, sizeof(t), ok, ",\"children\":[1]", "\"scene\":0,", "3");
  expect(gltf, t, "does not exist");
  expect(gltf, "{\"asset\":{\"version\":\"2.0\"}}", "no meshes");
  expect(gltf,
    "[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[]]]]]]]]]]]]]]]]]]]]]]]]]]"
    "]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]",
    "not valid");
  expect(gltf,
    "{\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0}}]}],\"buffers\":[{"
    "\"byteLength\":4}]}",
    "no 'uri'");
}

static void test_xml(void)
{
  char t[1024];
  static const char* const piece =
    "<?xml version=\"1.0\"?><VTKFile type=\"PolyData\" header_type=\"UInt32\">"
    "<PolyData><Piece NumberOfPoints=\"%s\"><Points><DataArray type=\"Float32\" "
    "NumberOfComponents=\"%s\" format=\"%s\" offset=\"%s\"/></Points></Piece>"
    "</PolyData><AppendedData encoding=\"raw\">_%s</AppendedData></VTKFile>";
  snprintf(t, sizeof(t), piece, "1", "3", "appended", "0", "HHHHabcdefghijkl");
  expect(xml, t, NULL);
  snprintf(t, sizeof(t), piece, "1", "3", "appended", "0", "\377\377\377\177abcdefghijkl");
  expect(xml, t, "declares 2147483647 bytes");
  snprintf(t, sizeof(t), piece, "1", "3", "appended", "9000", "HHHHabcdefghijkl");
  expect(xml, t, "offset 9000");
  snprintf(t, sizeof(t), piece, "2000000000", "3", "appended", "0", "HHHHabcdefghijkl");
  expect(xml, t, "NumberOfPoints");
  snprintf(t, sizeof(t), piece, "1", "2000000000", "appended", "0", "HHHHabcdefghijkl");
  expect(xml, t, "NumberOfComponents");
  expect(xml, "<VTKFile type=\"ImageData\"><ImageData WholeExtent=\"0 99999 0 99999 0 99999\">",
    "WholeExtent");
  expect(xml, "<VTKFile type=\"ImageData\"><ImageData WholeExtent=\"3 0 0 1 0 1\">", "WholeExtent");
  expect(xml, "no xml", "no VTKFile");
}

static void test_not_regular_files(void)
{
  mrgi_error err;
  char dir[512], fifo[512];
  mrgi_test_tmp_path("input-dir.ply", dir, sizeof(dir));
  mrgi_test_tmp_path("input-fifo.obj", fifo, sizeof(fifo));
  mkdir(dir, 0700);
  unlink(fifo);
  MRGI_CHECK(mkfifo(fifo, 0600) == 0);
  MRGI_CHECK(
    mrgi_ply_check(dir, NULL, &err) == MRGI_ERR_IO && strstr(err.message, "is a directory"));
  MRGI_CHECK(mrgi_obj_check(fifo, NULL, &err) == MRGI_ERR_IO && strstr(err.message, "FIFO"));
  MRGI_CHECK(
    mrgi_vtk_check("/dev/zero", NULL, &err) == MRGI_ERR_IO && strstr(err.message, "device"));
  MRGI_CHECK(mrgi_gltf_check("/nonexistent/x.gltf", NULL, &err) == MRGI_ERR_IO &&
    strstr(err.message, "cannot open"));
  unlink(fifo);
  rmdir(dir);
}

static void test_line_cursor(void)
{
  mrgi_line_cursor c;
  char line[8];
  mrgi_line_cursor_init(&c, "ab\r\ncdefghijk\nx", 15);
  MRGI_CHECK(mrgi_line_next(&c, line, sizeof(line)) == 1 && strcmp(line, "ab") == 0);
  MRGI_CHECK(mrgi_line_next(&c, line, sizeof(line)) == -1);
  mrgi_line_cursor_init(&c, "x", 1);
  MRGI_CHECK(mrgi_line_next(&c, line, sizeof(line)) == 1 && strcmp(line, "x") == 0);
  MRGI_CHECK(mrgi_line_next(&c, line, sizeof(line)) == 0);
}

int main(int argc, char** argv)
{
  static const mrgi_test_case cases[] = {
    MRGI_TEST_CASE(test_obj),
    MRGI_TEST_CASE(test_vtk),
    MRGI_TEST_CASE(test_ply),
    MRGI_TEST_CASE(test_gltf),
    MRGI_TEST_CASE(test_xml),
    MRGI_TEST_CASE(test_not_regular_files),
    MRGI_TEST_CASE(test_line_cursor),
  };
  return MRGI_TEST_MAIN(argc, argv, cases);
}
