// The G-buffer albedo is the colour VTK shades with, whatever its source:
// - scalars through a lookup table (cell scalars; point scalars interpolated
//   before mapping, which VTK draws through a colour texture): LUT colour x Diffuse;
// - direct RGB scalars: the scalar colour x Diffuse;
// - a texture: texel colour x Diffuse (VTK modulates its lit colour by it);
// - a solid colour: colour x Diffuse;
// - PBR actors: the base colour, and base colour x base-colour-texture texel.
// Indirect light reaches every one of them (no NaN); with IndirectMode Off
// the image is VTK's own (max difference 1/255).
#include "TestMRGIPipelineCommon.h"

#include "vtkCellData.h"
#include "vtkLight.h"
#include "vtkLookupTable.h"
#include "vtkTexture.h"
#include "vtkUnsignedCharArray.h"

#include <vector>

namespace
{
// A 2 x 2 RGB texture, nearest-neighbour: texel (i, j) is colours[j][i].
vtkSmartPointer<vtkTexture> MakeTexture(const unsigned char colours[2][2][3])
{
  vtkNew<vtkImageData> image;
  image->SetDimensions(2, 2, 1);
  image->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
  for (int j = 0; j < 2; ++j)
  {
    for (int i = 0; i < 2; ++i)
    {
      for (int c = 0; c < 3; ++c)
      {
        image->SetScalarComponentFromDouble(i, j, 0, c, colours[j][i][c]);
      }
    }
  }
  auto texture = vtkSmartPointer<vtkTexture>::New();
  texture->SetInputData(image);
  texture->InterpolateOff();
  texture->RepeatOff();
  texture->EdgeClampOn();
  return texture;
}

// A unit square facing +z, centred at (cx, cy, 0), 2 x 2 cells, with texture coordinates.
vtkSmartPointer<vtkPolyData> Square(double cx, double cy)
{
  vtkNew<vtkPlaneSource> plane;
  plane->SetOrigin(cx - 0.5, cy - 0.5, 0);
  plane->SetPoint1(cx + 0.5, cy - 0.5, 0);
  plane->SetPoint2(cx - 0.5, cy + 0.5, 0);
  plane->SetResolution(2, 2);
  plane->Update();
  return plane->GetOutput();
}

struct Expectation
{
  const char* What;
  double World[2]; // a point well inside one colour region
  double Albedo[3];
};
}

int main()
{
  using namespace mrgipipe;
  const int W = 160, H = 120;
  vtkSmartPointer<vtkRenderWindow> window = mrgitest::HeadlessWindow(W, H);
  vtkNew<vtkRenderer> renderer;
  window->AddRenderer(renderer);
  std::vector<Expectation> expected;
  const double q = 0.25; // quarter of a square: the centre of a 2 x 2 cell block's cell

  // 1. Cell scalars 0 | 1 (left | right half) through a two-colour lookup table, Diffuse 0.8.
  vtkNew<vtkLookupTable> lut;
  lut->SetNumberOfTableValues(2);
  lut->SetTableRange(0, 1);
  lut->SetTableValue(0, 0.8, 0.2, 0.1, 1.0);
  lut->SetTableValue(1, 0.1, 0.3, 0.9, 1.0);
  lut->Build();
  {
    vtkSmartPointer<vtkPolyData> square = Square(-1.2, 0.6);
    vtkNew<vtkFloatArray> scalars;
    scalars->SetName("side");
    for (vtkIdType c = 0; c < square->GetNumberOfCells(); ++c)
    {
      double centre[3] = { 0, 0, 0 }, p[3];
      vtkCell* cell = square->GetCell(c);
      for (vtkIdType k = 0; k < cell->GetNumberOfPoints(); ++k)
      {
        square->GetPoint(cell->GetPointId(k), p);
        centre[0] += p[0] / cell->GetNumberOfPoints();
      }
      scalars->InsertNextValue(centre[0] < -1.2 ? 0.0f : 1.0f);
    }
    square->GetCellData()->SetScalars(scalars);
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputData(square);
    mapper->SetLookupTable(lut);
    mapper->SetScalarModeToUseCellData();
    mapper->SetScalarRange(0, 1);
    mapper->ScalarVisibilityOn();
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    actor->GetProperty()->SetDiffuse(0.8);
    actor->GetProperty()->SetSpecular(0);
    renderer->AddActor(actor);
    // The mapped colours are unsigned char: LUT value rounded to 1/255.
    const unsigned char* left = lut->MapValue(0.0);
    const unsigned char* right = lut->MapValue(1.0);
    expected.push_back({ "cell scalars, LUT entry 0", { -1.2 - q, 0.6 },
      { 0.8 * left[0] / 255.0, 0.8 * left[1] / 255.0, 0.8 * left[2] / 255.0 } });
    expected.push_back({ "cell scalars, LUT entry 1", { -1.2 + q, 0.6 },
      { 0.8 * right[0] / 255.0, 0.8 * right[1] / 255.0, 0.8 * right[2] / 255.0 } });
  }

  // 2. Point scalars interpolated before mapping (VTK's colour-texture path), Diffuse 0.6.
  vtkNew<vtkLookupTable> ramp;
  ramp->SetNumberOfTableValues(4);
  ramp->SetTableRange(0, 4);
  ramp->SetTableValue(0, 1.0, 0.0, 0.0, 1.0);
  ramp->SetTableValue(1, 0.2, 0.7, 0.3, 1.0);
  ramp->SetTableValue(2, 0.0, 0.0, 1.0, 1.0);
  ramp->SetTableValue(3, 1.0, 1.0, 0.0, 1.0);
  ramp->Build();
  {
    vtkSmartPointer<vtkPolyData> square = Square(0.0, 0.6);
    vtkNew<vtkFloatArray> scalars;
    scalars->SetName("value");
    for (vtkIdType p = 0; p < square->GetNumberOfPoints(); ++p)
    {
      scalars->InsertNextValue(1.5f); // the middle of entry 1
    }
    square->GetPointData()->SetScalars(scalars);
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputData(square);
    mapper->SetLookupTable(ramp);
    mapper->SetScalarRange(0, 4);
    mapper->InterpolateScalarsBeforeMappingOn();
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    actor->GetProperty()->SetDiffuse(0.6);
    actor->GetProperty()->SetSpecular(0);
    renderer->AddActor(actor);
    const unsigned char* c = ramp->MapValue(1.5);
    expected.push_back({ "point scalars, interpolated before mapping", { 0.0, 0.6 },
      { 0.6 * c[0] / 255.0, 0.6 * c[1] / 255.0, 0.6 * c[2] / 255.0 } });
  }

  // 3. Direct RGB scalars (no lookup table), Diffuse 1.
  {
    vtkSmartPointer<vtkPolyData> square = Square(1.2, 0.6);
    vtkNew<vtkUnsignedCharArray> colours;
    colours->SetNumberOfComponents(3);
    colours->SetName("rgb");
    for (vtkIdType p = 0; p < square->GetNumberOfPoints(); ++p)
    {
      colours->InsertNextTuple3(40, 200, 120);
    }
    square->GetPointData()->SetScalars(colours);
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputData(square);
    mapper->SetColorModeToDirectScalars();
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    actor->GetProperty()->SetSpecular(0);
    renderer->AddActor(actor);
    expected.push_back(
      { "direct RGB scalars", { 1.2, 0.6 }, { 40 / 255.0, 200 / 255.0, 120 / 255.0 } });
  }

  // 4. A 2 x 2 texture, Diffuse 0.9: each quarter of the square one texel.
  const unsigned char texels[2][2][3] = { { { 250, 20, 20 }, { 20, 250, 20 } },
    { { 20, 20, 250 }, { 230, 230, 30 } } };
  {
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputData(Square(-1.2, -0.6));
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    actor->SetTexture(MakeTexture(texels));
    actor->GetProperty()->SetDiffuse(0.9);
    actor->GetProperty()->SetSpecular(0);
    renderer->AddActor(actor);
    for (int j = 0; j < 2; ++j)
    {
      for (int i = 0; i < 2; ++i)
      {
        Expectation e{ "texture texel", { -1.2 + (i ? q : -q), -0.6 + (j ? q : -q) }, { 0, 0, 0 } };
        for (int c = 0; c < 3; ++c)
        {
          e.Albedo[c] = 0.9 * texels[j][i][c] / 255.0;
        }
        expected.push_back(e);
      }
    }
  }

  // 5. A solid colour, Diffuse 0.7.
  {
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputData(Square(0.0, -0.6));
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    actor->GetProperty()->SetColor(0.3, 0.6, 0.9);
    actor->GetProperty()->SetDiffuse(0.7);
    actor->GetProperty()->SetSpecular(0);
    renderer->AddActor(actor);
    expected.push_back({ "solid colour", { 0.0, -0.6 }, { 0.21, 0.42, 0.63 } });
  }

  // 6. PBR: the left half of the square alone is the base colour (a square of
  // its own), the right half is base colour x base-colour texture.
  {
    vtkNew<vtkPlaneSource> left;
    left->SetOrigin(0.7, -1.1, 0);
    left->SetPoint1(1.2, -1.1, 0);
    left->SetPoint2(0.7, -0.1, 0);
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputConnection(left->GetOutputPort());
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    actor->GetProperty()->SetInterpolationToPBR();
    actor->GetProperty()->SetColor(0.9, 0.5, 0.2);
    actor->GetProperty()->SetMetallic(0.0);
    actor->GetProperty()->SetRoughness(0.6);
    renderer->AddActor(actor);
    expected.push_back({ "PBR base colour", { 0.95, -0.6 }, { 0.9, 0.5, 0.2 } });

    vtkNew<vtkPlaneSource> right;
    right->SetOrigin(1.2, -1.1, 0);
    right->SetPoint1(1.7, -1.1, 0);
    right->SetPoint2(1.2, -0.1, 0);
    vtkNew<vtkPolyDataMapper> texturedMapper;
    texturedMapper->SetInputConnection(right->GetOutputPort());
    vtkNew<vtkActor> textured;
    textured->SetMapper(texturedMapper);
    textured->GetProperty()->SetInterpolationToPBR();
    textured->GetProperty()->SetColor(0.8, 0.8, 0.5);
    textured->GetProperty()->SetMetallic(0.0);
    textured->GetProperty()->SetRoughness(0.6);
    const unsigned char flat[2][2][3] = { { { 100, 200, 250 }, { 100, 200, 250 } },
      { { 100, 200, 250 }, { 100, 200, 250 } } };
    vtkSmartPointer<vtkTexture> baseColour = MakeTexture(flat);
    baseColour->UseSRGBColorSpaceOn(); // as VTK requires of base colour textures
    textured->GetProperty()->SetBaseColorTexture(baseColour);
    renderer->AddActor(textured);
    // sRGB texels are read as linear values.
    auto linear = [](double c)
    {
      c /= 255.0;
      return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
    };
    expected.push_back({ "PBR base colour x texture", { 1.45, -0.6 },
      { 0.8 * linear(100), 0.8 * linear(200), 0.5 * linear(250) } });
  }

  // A floor below and a light above: indirect light reaches the squares.
  const double cf[3] = { 0, -1.2, 1.0 }, nf[3] = { 0, 1, 0 };
  renderer->AddActor(MakeQuad(cf, nf, 4, 0.9, 0.9, 0.9));
  vtkNew<vtkLight> light;
  light->SetLightTypeToSceneLight();
  light->SetPositional(true);
  light->SetConeAngle(60);
  light->SetPosition(0, 1.5, 3.0);
  light->SetFocalPoint(0, -0.6, 0);
  renderer->AddLight(light);
  renderer->GetActiveCamera()->SetPosition(0, 0, 5);
  renderer->GetActiveCamera()->SetFocalPoint(0, 0, 0);
  renderer->GetActiveCamera()->SetViewAngle(32);
  renderer->ResetCameraClippingRange();

  window->Render();
  vtkSmartPointer<vtkImageData> plain = mrgitest::GrabRGB(window);
  vtkSmartPointer<vtkMRGIPass> pass = Install(renderer);
  pass->SetRSMResolution(128);
  pass->SetIndirectMode(vtkMRGIPass::IndirectOff);
  window->Render();
  vtkSmartPointer<vtkImageData> off = mrgitest::GrabRGB(window);
  std::printf("IndirectMode Off vs VTK: max difference %.0f / 255\n", MaxDifference(plain, off));
  MRGI_TEST_CHECK(MaxDifference(plain, off) <= 1.0);

  pass->SetIndirectMode(vtkMRGIPass::IndirectFull);
  window->Render();
  DebugWrite(mrgitest::GrabRGB(window), "TestMRGIPipelineColors");
  MRGI_TEST_CHECK(pass->GetIndirectComputed());
  vtkNew<vtkImageData> position, normal, albedo, indirect, colour;
  MRGI_TEST_CHECK(pass->GetGBuffer(window, position, normal, albedo));
  MRGI_TEST_CHECK(pass->GetIndirectBuffer(window, indirect));
  MRGI_TEST_CHECK(pass->GetColorBuffer(window, colour));
  MRGI_TEST_CHECK(AllFinite(indirect) && AllFinite(colour) && AllFinite(albedo));

  bool ok = true;
  for (const Expectation& e : expected)
  {
    renderer->SetWorldPoint(e.World[0], e.World[1], 0.0, 1.0);
    renderer->WorldToDisplay();
    const int px = static_cast<int>(renderer->GetDisplayPoint()[0]);
    const int py = static_cast<int>(renderer->GetDisplayPoint()[1]);
    // A 3 x 3 block of pixels well inside the region.
    double worst = 0;
    double got[3] = { 0, 0, 0 };
    double lit[3] = { 0, 0, 0 };
    for (int dy = -1; dy <= 1; ++dy)
    {
      for (int dx = -1; dx <= 1; ++dx)
      {
        MRGI_TEST_CHECK(Valid(albedo, px + dx, py + dy));
        for (int c = 0; c < 3; ++c)
        {
          const double a = At(albedo, px + dx, py + dy, c);
          worst = std::max(worst, std::fabs(a - e.Albedo[c]));
          got[c] += a / 9;
          lit[c] += At(indirect, px + dx, py + dy, c) / 9;
        }
      }
    }
    // Half floats hold 11 significant bits: 0.001 at 1.
    const bool good = worst < 0.003;
    std::printf("%-45s expected %.3f %.3f %.3f got %.3f %.3f %.3f (max error %.4f), indirect "
                "%.4f %.4f %.4f %s\n",
      e.What, e.Albedo[0], e.Albedo[1], e.Albedo[2], got[0], got[1], got[2], worst, lit[0], lit[1],
      lit[2], good ? "" : "<- WRONG");
    ok = ok && good;
    // Indirect light from the floor arrives, tinted by the albedo (no channel
    // of a coloured surface gets more than its albedo lets through).
    MRGI_TEST_CHECK(lit[0] + lit[1] + lit[2] > 1e-3);
  }
  MRGI_TEST_CHECK(ok);

  Uninstall(renderer, window, pass);
  return 0;
}
