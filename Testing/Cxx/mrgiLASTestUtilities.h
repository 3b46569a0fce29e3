/**
 * @file mrgiLASTestUtilities.h
 * @brief Writes LAS files for the C++ tests, byte by byte from the ASPRS
 *        specification (public header block, point formats 0-3 and 6-8):
 *        the tests must not trust the reader they check.
 */
#ifndef mrgiLASTestUtilities_h
#define mrgiLASTestUtilities_h

#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

namespace mrgitest
{
struct LASPoint
{
  double X = 0, Y = 0, Z = 0;
  uint16_t Intensity = 0;
  uint8_t ReturnNumber = 1, NumberOfReturns = 1, Classification = 0;
  uint16_t RGB[3] = { 0, 0, 0 };
};

struct LASFile
{
  int Minor = 2;  ///< version 1.Minor
  int Format = 0; ///< point format 0-3, 6-8
  double Scale[3] = { 0.001, 0.001, 0.001 };
  double Offset[3] = { 0, 0, 0 };
};

inline int LASHeaderSize(int minor)
{
  return minor >= 4 ? 375 : minor == 3 ? 235 : 227;
}

inline int LASRecordLength(int format)
{
  static const int lengths[11] = { 20, 28, 26, 34, 57, 63, 30, 36, 38, 59, 67 };
  return lengths[format];
}

inline void LASPut(std::vector<unsigned char>& b, size_t at, uint64_t v, int bytes)
{
  for (int i = 0; i < bytes; ++i)
  {
    b[at + static_cast<size_t>(i)] = static_cast<unsigned char>((v >> (8 * i)) & 0xFF);
  }
}

inline void LASPutDouble(std::vector<unsigned char>& b, size_t at, double v)
{
  uint64_t u;
  std::memcpy(&u, &v, sizeof(u));
  LASPut(b, at, u, 8);
}

/** The public header block for `count` points. */
inline std::vector<unsigned char> LASHeader(const LASFile& f, uint64_t count)
{
  const int header = LASHeaderSize(f.Minor);
  std::vector<unsigned char> b(static_cast<size_t>(header), 0);
  std::memcpy(b.data(), "LASF", 4);
  b[24] = 1;
  b[25] = static_cast<unsigned char>(f.Minor);
  LASPut(b, 94, static_cast<uint64_t>(header), 2);
  LASPut(b, 96, static_cast<uint64_t>(header), 4);
  b[104] = static_cast<unsigned char>(f.Format);
  LASPut(b, 105, static_cast<uint64_t>(LASRecordLength(f.Format)), 2);
  LASPut(b, 107, f.Minor >= 4 ? 0 : count, 4);
  if (f.Minor >= 4)
  {
    LASPut(b, 247, count, 8);
  }
  for (int c = 0; c < 3; ++c)
  {
    LASPutDouble(b, 131 + 8 * static_cast<size_t>(c), f.Scale[c]);
    LASPutDouble(b, 155 + 8 * static_cast<size_t>(c), f.Offset[c]);
  }
  return b;
}

/** Appends one point record of `f.Format` to `b`. */
inline void LASAppend(std::vector<unsigned char>& b, const LASFile& f, const LASPoint& p)
{
  const size_t r = b.size();
  b.resize(r + static_cast<size_t>(LASRecordLength(f.Format)), 0);
  const double xyz[3] = { p.X, p.Y, p.Z };
  for (int c = 0; c < 3; ++c)
  {
    const auto v = static_cast<int32_t>(std::llround((xyz[c] - f.Offset[c]) / f.Scale[c]));
    LASPut(b, r + 4 * static_cast<size_t>(c), static_cast<uint32_t>(v), 4);
  }
  LASPut(b, r + 12, p.Intensity, 2);
  int rgb = -1;
  if (f.Format >= 6)
  {
    b[r + 14] = static_cast<unsigned char>(p.ReturnNumber | (p.NumberOfReturns << 4));
    b[r + 16] = p.Classification;
    rgb = f.Format >= 7 ? 30 : -1;
  }
  else
  {
    b[r + 14] = static_cast<unsigned char>(p.ReturnNumber | (p.NumberOfReturns << 3));
    b[r + 15] = p.Classification;
    rgb = f.Format == 2 ? 20 : f.Format == 3 ? 28 : -1;
  }
  for (int c = 0; rgb >= 0 && c < 3; ++c)
  {
    LASPut(b, r + static_cast<size_t>(rgb + 2 * c), p.RGB[c], 2);
  }
}

/** A whole LAS file in memory. */
inline std::vector<unsigned char> LASBytes(const LASFile& f, const std::vector<LASPoint>& points)
{
  std::vector<unsigned char> b = LASHeader(f, points.size());
  for (const LASPoint& p : points)
  {
    LASAppend(b, f, p);
  }
  return b;
}

inline void WriteBytes(const std::string& path, const std::vector<unsigned char>& b)
{
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(b.data()), static_cast<std::streamsize>(b.size()));
}
}

#endif
