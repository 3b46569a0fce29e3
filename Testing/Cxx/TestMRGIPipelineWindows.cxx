// vtkMRGIPass in the windows applications have:
// 1. non-square windows and resizing: a 320 x 200 window resized to 150 x 300
//    and to 100 x 80 renders what a fresh window of that size renders (no
//    stale buffers), with buffers of the new size; a gradient background is
//    VTK's and gets no indirect light;
// 2. several renderers in one window: two side by side, each with its own
//    vtkMRGIPass, each half as a window of its own would show it; one with
//    MRGI and one without: the one without is untouched;
// 3. a second renderer layer: a renderer in layer 1 (what an orientation
//    marker uses) and a real vtkOrientationMarkerWidget with a vtkAxesActor:
//    the marker's pixels appear as VTK draws them, the rest of the image is
//    unchanged by them.
// 4. two windows sharing their actors, each with its own pass, rendered in
//    turn: each shows what a window of its own shows.
// With IndirectMode Off every image is VTK's own (max difference 1/255).
//
// The widget and axes actor live in VTK modules the C++ tests do not link
// (InteractionWidgets, RenderingAnnotation): they are loaded at run time
// (TestMRGIPipelineCommon.h).
#include "TestMRGIPipelineCommon.h"

#include "vtkAxesActor.h"
#include "vtkGenericRenderWindowInteractor.h"

#include "vtkConeSource.h"
#include "vtkCubeSource.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkActorCollection.h"
#include "vtkOrientationMarkerWidget.h"
#include "vtkRenderWindowInteractor.h"
#include "vtkRendererCollection.h"

namespace
{
// A small lit room with a coloured box; `tint` tells the scenes apart.
void BuildScene(vtkRenderer* renderer, double r, double g, double b)
{
  const double cf[3] = { 0, -1, 0 }, nf[3] = { 0, 1, 0 };
  const double cw[3] = { 0, 0.5, -1.5 }, nw[3] = { 0, 0, 1 };
  renderer->AddActor(mrgipipe::MakeQuad(cf, nf, 3, 0.8, 0.8, 0.8, 4));
  renderer->AddActor(mrgipipe::MakeQuad(cw, nw, 3, 0.8, 0.8, 0.8, 4));
  vtkNew<vtkCubeSource> cube;
  vtkSmartPointer<vtkActor> box = mrgipipe::MakeActor(cube, r, g, b);
  box->SetPosition(-0.2, -0.5, -0.4);
  box->RotateY(25);
  renderer->AddActor(box);
  vtkNew<vtkLight> light;
  light->SetLightTypeToSceneLight();
  light->SetPositional(true);
  light->SetConeAngle(50);
  light->SetPosition(0.8, 2.5, 2.0);
  light->SetFocalPoint(0, -0.8, -0.3);
  renderer->AddLight(light);
  renderer->SetBackground(0.1, 0.1, 0.15);
  renderer->GetActiveCamera()->SetPosition(0.3, 0.6, 4.5);
  renderer->GetActiveCamera()->SetFocalPoint(0, -0.2, 0);
  renderer->ResetCameraClippingRange();
}

// The scene in a fresh window of w x h, with MRGI (mode) or without (mode < 0).
vtkSmartPointer<vtkImageData> Fresh(int w, int h, int mode, double r, double g, double b)
{
  vtkSmartPointer<vtkRenderWindow> window = mrgitest::HeadlessWindow(w, h);
  vtkNew<vtkRenderer> renderer;
  window->AddRenderer(renderer);
  BuildScene(renderer, r, g, b);
  vtkSmartPointer<vtkMRGIPass> pass;
  if (mode >= 0)
  {
    pass = mrgipipe::Install(renderer);
    pass->SetRSMResolution(64);
    pass->SetIndirectMode(mode);
  }
  window->Render();
  vtkSmartPointer<vtkImageData> image = mrgitest::GrabRGB(window);
  if (pass)
  {
    mrgipipe::Uninstall(renderer, window, pass);
  }
  return image;
}

// The pixels [x0, x0 + w) x [y0, y0 + h) of `image`.
vtkSmartPointer<vtkImageData> Crop(vtkImageData* image, int x0, int y0, int w, int h)
{
  auto out = vtkSmartPointer<vtkImageData>::New();
  out->SetDimensions(w, h, 1);
  out->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
  for (int y = 0; y < h; ++y)
  {
    for (int x = 0; x < w; ++x)
    {
      for (int c = 0; c < 3; ++c)
      {
        out->SetScalarComponentFromDouble(
          x, y, 0, c, image->GetScalarComponentAsDouble(x0 + x, y0 + y, 0, c));
      }
    }
  }
  return out;
}
}

int main()
{
  using namespace mrgipipe;

  // 1. Non-square window, then resized.
  {
    vtkSmartPointer<vtkRenderWindow> window = mrgitest::HeadlessWindow(320, 200);
    vtkNew<vtkRenderer> renderer;
    window->AddRenderer(renderer);
    BuildScene(renderer, 0.9, 0.2, 0.1);
    window->Render();
    vtkSmartPointer<vtkImageData> plain = mrgitest::GrabRGB(window);
    vtkSmartPointer<vtkMRGIPass> pass = Install(renderer);
    pass->SetRSMResolution(64);
    pass->SetIndirectMode(vtkMRGIPass::IndirectOff);
    window->Render();
    std::printf("320 x 200: IndirectMode Off vs VTK max difference %.0f\n",
      MaxDifference(plain, mrgitest::GrabRGB(window)));
    MRGI_TEST_CHECK(MaxDifference(plain, mrgitest::GrabRGB(window)) <= 1.0);
    pass->SetIndirectMode(vtkMRGIPass::IndirectFull);
    window->Render();
    MRGI_TEST_CHECK(pass->GetIndirectComputed());
    MRGI_TEST_CHECK(
      MaxDifference(mrgitest::GrabRGB(window), Fresh(320, 200, 1, 0.9, 0.2, 0.1)) <= 1.0);
    const int sizes[2][2] = { { 150, 300 }, { 100, 80 } };
    for (const auto& size : sizes)
    {
      window->SetSize(size[0], size[1]);
      window->Render();
      MRGI_TEST_CHECK(pass->GetIndirectComputed());
      MRGI_TEST_CHECK(pass->GetBufferSize()[0] == size[0] && pass->GetBufferSize()[1] == size[1]);
      vtkNew<vtkImageData> colour, position, normal, albedo;
      MRGI_TEST_CHECK(pass->GetColorBuffer(window, colour));
      MRGI_TEST_CHECK(pass->GetGBuffer(window, position, normal, albedo));
      int dims[3];
      colour->GetDimensions(dims);
      MRGI_TEST_CHECK(dims[0] == size[0] && dims[1] == size[1] && AllFinite(colour));
      position->GetDimensions(dims);
      MRGI_TEST_CHECK(dims[0] == size[0] && dims[1] == size[1]);
      vtkSmartPointer<vtkImageData> resized = mrgitest::GrabRGB(window);
      vtkSmartPointer<vtkImageData> fresh = Fresh(size[0], size[1], 1, 0.9, 0.2, 0.1);
      DebugWrite(resized, "TestMRGIPipelineWindows-resized-" + std::to_string(size[0]));
      DebugWrite(fresh, "TestMRGIPipelineWindows-fresh-" + std::to_string(size[0]));
      std::printf("resized to %d x %d: max difference to a fresh window %.0f\n", size[0], size[1],
        MaxDifference(resized, fresh));
      MRGI_TEST_CHECK(MaxDifference(resized, fresh) <= 1.0);
      MRGI_TEST_CHECK(MaxDifference(resized, Fresh(size[0], size[1], -1, 0.9, 0.2, 0.1)) > 10);
    }
    // A gradient background (drawn by VTK's clear, before MRGI's G-buffer
    // clear): the same as VTK's, and nothing added where no surface is.
    renderer->GradientBackgroundOn();
    renderer->SetBackground2(0.5, 0.6, 0.9);
    window->Render();
    vtkSmartPointer<vtkImageData> gradientFull = mrgitest::GrabRGB(window);
    vtkNew<vtkImageData> position, normal, albedo;
    MRGI_TEST_CHECK(pass->GetGBuffer(window, position, normal, albedo));
    pass->SetIndirectMode(vtkMRGIPass::IndirectOff);
    window->Render();
    vtkSmartPointer<vtkImageData> gradientOff = mrgitest::GrabRGB(window);
    renderer->SetPass(nullptr);
    window->Render();
    vtkSmartPointer<vtkImageData> gradientPlain = mrgitest::GrabRGB(window);
    int background = 0;
    double worst = 0;
    for (int y = 0; y < 80; ++y)
    {
      for (int x = 0; x < 100; ++x)
      {
        if (!Valid(position, x, y))
        {
          ++background;
          for (int c = 0; c < 3; ++c)
          {
            worst = std::max(worst,
              std::fabs(gradientFull->GetScalarComponentAsDouble(x, y, 0, c) -
                gradientOff->GetScalarComponentAsDouble(x, y, 0, c)));
          }
        }
      }
    }
    std::printf("gradient background: IndirectMode Off vs VTK %.0f; %d background pixels, on vs "
                "off %.0f\n",
      MaxDifference(gradientOff, gradientPlain), background, worst);
    MRGI_TEST_CHECK(MaxDifference(gradientOff, gradientPlain) <= 1.0);
    MRGI_TEST_CHECK(background > 100 && worst <= 1.0);
    pass->ReleaseGraphicsResources(window);
  }

  // 2. Two renderers side by side.
  {
    const int W = 320, H = 160;
    vtkSmartPointer<vtkRenderWindow> window = mrgitest::HeadlessWindow(W, H);
    vtkNew<vtkRenderer> left, right;
    left->SetViewport(0, 0, 0.5, 1);
    right->SetViewport(0.5, 0, 1, 1);
    window->AddRenderer(left);
    window->AddRenderer(right);
    BuildScene(left, 0.9, 0.2, 0.1);
    BuildScene(right, 0.1, 0.3, 0.9);
    vtkSmartPointer<vtkMRGIPass> leftPass = Install(left);
    vtkSmartPointer<vtkMRGIPass> rightPass = Install(right);
    leftPass->SetRSMResolution(64);
    rightPass->SetRSMResolution(64);
    // The multiresolution gather: its buffers and passes at a viewport offset.
    leftPass->SetIndirectMode(vtkMRGIPass::IndirectMultires);
    rightPass->SetIndirectMode(vtkMRGIPass::IndirectMultires);
    window->Render();
    MRGI_TEST_CHECK(leftPass->GetIndirectComputed() && rightPass->GetIndirectComputed());
    MRGI_TEST_CHECK(leftPass->GetBufferSize()[0] == 160 && rightPass->GetBufferSize()[0] == 160);
    vtkSmartPointer<vtkImageData> both = mrgitest::GrabRGB(window);
    DebugWrite(both, "TestMRGIPipelineWindows-two-mrgi");
    const int multires = vtkMRGIPass::IndirectMultires;
    const double dl = MaxDifference(Crop(both, 0, 0, 160, 160), Fresh(160, 160, multires, 0.9, 0.2, 0.1));
    const double dr =
      MaxDifference(Crop(both, 160, 0, 160, 160), Fresh(160, 160, multires, 0.1, 0.3, 0.9));
    std::printf("two MRGI viewports: left vs own window %.0f, right vs own window %.0f\n", dl, dr);
    MRGI_TEST_CHECK(dl <= 1.0 && dr <= 1.0);
    // Each pass's buffers are its own viewport's.
    vtkNew<vtkImageData> leftColour, rightColour;
    MRGI_TEST_CHECK(leftPass->GetColorBuffer(window, leftColour));
    MRGI_TEST_CHECK(rightPass->GetColorBuffer(window, rightColour));
    int dims[3];
    rightColour->GetDimensions(dims);
    MRGI_TEST_CHECK(dims[0] == 160 && dims[1] == 160);
    // Blue box on the right, red on the left: the right pass's buffer is bluer.
    const double lr = SumRGB(leftColour, 0, 0, 160, 160), rr = SumRGB(rightColour, 0, 0, 160, 160);
    double lrgb[3], rrgb[3];
    SumRGB(leftColour, 0, 0, 160, 160, lrgb);
    SumRGB(rightColour, 0, 0, 160, 160, rrgb);
    MRGI_TEST_CHECK(lr > 0 && rr > 0 && rrgb[2] / rr > lrgb[2] / lr && lrgb[0] / lr > rrgb[0] / rr);

    // With IndirectMode Off both halves are VTK's.
    leftPass->SetIndirectMode(vtkMRGIPass::IndirectOff);
    rightPass->SetIndirectMode(vtkMRGIPass::IndirectOff);
    window->Render();
    vtkSmartPointer<vtkImageData> offBoth = mrgitest::GrabRGB(window);
    left->SetPass(nullptr);
    right->SetPass(nullptr);
    window->Render();
    vtkSmartPointer<vtkImageData> plainBoth = mrgitest::GrabRGB(window);
    std::printf("two viewports: IndirectMode Off vs VTK %.0f\n", MaxDifference(offBoth, plainBoth));
    MRGI_TEST_CHECK(MaxDifference(offBoth, plainBoth) <= 1.0);

    // MRGI on the left only: the right viewport is untouched.
    leftPass->SetIndirectMode(vtkMRGIPass::IndirectMultires);
    left->SetPass(leftPass);
    window->Render();
    vtkSmartPointer<vtkImageData> mixed = mrgitest::GrabRGB(window);
    DebugWrite(mixed, "TestMRGIPipelineWindows-mixed");
    const double ml = MaxDifference(Crop(mixed, 0, 0, 160, 160), Crop(both, 0, 0, 160, 160));
    const double mr =
      MaxDifference(Crop(mixed, 160, 0, 160, 160), Crop(plainBoth, 160, 0, 160, 160));
    std::printf("MRGI left only: left vs MRGI %.0f, right vs VTK %.0f\n", ml, mr);
    MRGI_TEST_CHECK(ml <= 1.0 && mr <= 1.0);
    MRGI_TEST_CHECK(
      MaxDifference(Crop(mixed, 0, 0, 160, 160), Crop(plainBoth, 0, 0, 160, 160)) > 10);
    // And the other way round.
    left->SetPass(nullptr);
    right->SetPass(rightPass);
    rightPass->SetIndirectMode(vtkMRGIPass::IndirectMultires);
    window->Render();
    mixed = mrgitest::GrabRGB(window);
    MRGI_TEST_CHECK(
      MaxDifference(Crop(mixed, 0, 0, 160, 160), Crop(plainBoth, 0, 0, 160, 160)) <= 1.0);
    MRGI_TEST_CHECK(
      MaxDifference(Crop(mixed, 160, 0, 160, 160), Crop(both, 160, 0, 160, 160)) <= 1.0);
    right->SetPass(nullptr);
    leftPass->ReleaseGraphicsResources(window);
    rightPass->ReleaseGraphicsResources(window);
  }

  // 3. A second layer: a renderer in layer 1 in a corner, then a real
  // orientation marker widget.
  {
    const int W = 200, H = 150;
    vtkSmartPointer<vtkRenderWindow> window = mrgitest::HeadlessWindow(W, H);
    vtkNew<vtkRenderer> renderer;
    window->AddRenderer(renderer);
    BuildScene(renderer, 0.9, 0.2, 0.1);
    window->SetNumberOfLayers(2);
    vtkNew<vtkRenderer> marker;
    marker->SetLayer(1);
    marker->SetViewport(0.0, 0.0, 0.3, 0.3);
    marker->InteractiveOff();
    vtkNew<vtkConeSource> cone;
    marker->AddActor(MakeActor(cone, 1.0, 0.9, 0.1));
    marker->ResetCamera();
    window->AddRenderer(marker);
    const int mx1 = static_cast<int>(0.3 * W), my1 = static_cast<int>(0.3 * H);

    window->Render();
    vtkSmartPointer<vtkImageData> plainWith = mrgitest::GrabRGB(window);
    DebugWrite(plainWith, "TestMRGIPipelineWindows-layer-plain");
    vtkSmartPointer<vtkMRGIPass> pass = Install(renderer);
    pass->SetRSMResolution(64);
    pass->SetIndirectMode(vtkMRGIPass::IndirectOff);
    window->Render();
    std::printf("layer 1: IndirectMode Off vs VTK %.0f\n",
      MaxDifference(plainWith, mrgitest::GrabRGB(window)));
    MRGI_TEST_CHECK(MaxDifference(plainWith, mrgitest::GrabRGB(window)) <= 1.0);
    pass->SetIndirectMode(vtkMRGIPass::IndirectFull);
    window->Render();
    MRGI_TEST_CHECK(pass->GetIndirectComputed());
    vtkSmartPointer<vtkImageData> withMarker = mrgitest::GrabRGB(window);
    DebugWrite(withMarker, "TestMRGIPipelineWindows-layer");
    marker->DrawOff();
    window->Render();
    vtkSmartPointer<vtkImageData> withoutMarker = mrgitest::GrabRGB(window);
    marker->DrawOn();
    renderer->SetPass(nullptr);
    marker->DrawOff();
    window->Render();
    vtkSmartPointer<vtkImageData> plainWithout = mrgitest::GrabRGB(window);
    marker->DrawOn();
    renderer->SetPass(pass);
    // The cone's pixels: where VTK's image changes with the marker.
    int conePixels = 0, wrong = 0;
    for (int y = 0; y < my1; ++y)
    {
      for (int x = 0; x < mx1; ++x)
      {
        bool onCone = false, same = true;
        for (int c = 0; c < 3; ++c)
        {
          onCone = onCone ||
            std::fabs(plainWith->GetScalarComponentAsDouble(x, y, 0, c) -
              plainWithout->GetScalarComponentAsDouble(x, y, 0, c)) > 30;
          same = same &&
            std::fabs(withMarker->GetScalarComponentAsDouble(x, y, 0, c) -
              plainWith->GetScalarComponentAsDouble(x, y, 0, c)) <= 1;
        }
        conePixels += onCone ? 1 : 0;
        wrong += (onCone && !same) ? 1 : 0;
      }
    }
    std::printf("layer 1 cone: %d pixels, %d of them not as VTK draws them; outside the corner "
                "the marker changes %.0f\n",
      conePixels, wrong, MaxDifference(withMarker, withoutMarker, mx1, 0, W, H));
    MRGI_TEST_CHECK(conePixels > 100 && wrong == 0);
    MRGI_TEST_CHECK(MaxDifference(withMarker, withoutMarker, mx1, 0, W, H) <= 1.0);
    MRGI_TEST_CHECK(MaxDifference(withMarker, withoutMarker, 0, my1, W, H) <= 1.0);
    window->RemoveRenderer(marker);

    // A vtkOrientationMarkerWidget with a vtkAxesActor, driven by a headless
    // application's interactor (vtkRenderWindowInteractor::New() would be
    // the X11 one, which needs a display).
    vtkNew<vtkGenericRenderWindowInteractor> interactor;
    interactor->SetRenderWindow(window);
    vtkNew<vtkAxesActor> axes;
    vtkNew<vtkOrientationMarkerWidget> widget;
    widget->SetOrientationMarker(axes);
    widget->SetInteractor(interactor);
    widget->SetDefaultRenderer(renderer);
    widget->SetViewport(0.0, 0.0, 0.3, 0.3);
    widget->SetEnabled(1);
    MRGI_TEST_CHECK(window->GetRenderers()->GetNumberOfItems() == 2);
    window->Render();
    MRGI_TEST_CHECK(pass->GetIndirectComputed());
    vtkSmartPointer<vtkImageData> withAxes = mrgitest::GrabRGB(window);
    DebugWrite(withAxes, "TestMRGIPipelineWindows-widget");
    // Drawn in its corner over the indirectly lit scene, nothing else changed.
    const int axesPixels = CountDifferent(withAxes, withoutMarker, 30);
    std::printf("orientation marker widget: %d pixels drawn; outside the corner the widget "
                "changes %.0f\n",
      axesPixels, MaxDifference(withAxes, withoutMarker, mx1, 0, W, H));
    MRGI_TEST_CHECK(axesPixels > 50);
    MRGI_TEST_CHECK(MaxDifference(withAxes, withoutMarker, mx1, 0, W, H) <= 1.0);
    MRGI_TEST_CHECK(MaxDifference(withAxes, withoutMarker, 0, my1, W, H) <= 1.0);
    // With indirect light off, exactly as VTK draws it (its labels are
    // antialiased over the scene, so this is where they can be compared).
    pass->SetIndirectMode(vtkMRGIPass::IndirectOff);
    window->Render();
    vtkSmartPointer<vtkImageData> offAxes = mrgitest::GrabRGB(window);
    renderer->SetPass(nullptr);
    window->Render();
    vtkSmartPointer<vtkImageData> plainAxes = mrgitest::GrabRGB(window);
    DebugWrite(plainAxes, "TestMRGIPipelineWindows-widget-plain");
    std::printf("orientation marker widget: IndirectMode Off vs VTK %.0f\n",
      MaxDifference(offAxes, plainAxes));
    MRGI_TEST_CHECK(MaxDifference(offAxes, plainAxes) <= 1.0);
    widget->SetEnabled(0);
    pass->ReleaseGraphicsResources(window);
  }

  // 4. Two windows sharing their actors, each with its own vtkMRGIPass,
  //    rendered in turn: VTK moves a shared mapper's buffers from one
  //    context to the other, freeing them in the first window's context
  //    (PushContext/PopContext). Each window shows what a window of its own
  //    shows, frame after frame.
  {
    const int w = 160, h = 120;
    vtkSmartPointer<vtkImageData> fresh = Fresh(w, h, vtkMRGIPass::IndirectFull, 0.9, 0.2, 0.1);
    vtkSmartPointer<vtkRenderWindow> first = mrgitest::HeadlessWindow(w, h);
    vtkSmartPointer<vtkRenderWindow> second = mrgitest::HeadlessWindow(w, h);
    vtkNew<vtkRenderer> firstRenderer, secondRenderer;
    first->AddRenderer(firstRenderer);
    second->AddRenderer(secondRenderer);
    BuildScene(firstRenderer, 0.9, 0.2, 0.1);
    vtkActorCollection* actors = firstRenderer->GetActors();
    actors->InitTraversal();
    while (vtkActor* actor = actors->GetNextActor())
    {
      secondRenderer->AddActor(actor);
    }
    firstRenderer->GetLights()->InitTraversal();
    while (vtkLight* light = firstRenderer->GetLights()->GetNextItem())
    {
      secondRenderer->AddLight(light);
    }
    secondRenderer->SetBackground(firstRenderer->GetBackground());
    secondRenderer->SetActiveCamera(firstRenderer->GetActiveCamera());
    vtkSmartPointer<vtkMRGIPass> firstPass = Install(firstRenderer);
    vtkSmartPointer<vtkMRGIPass> secondPass = Install(secondRenderer);
    for (vtkMRGIPass* p : { firstPass.Get(), secondPass.Get() })
    {
      p->SetRSMResolution(64);
      p->SetIndirectMode(vtkMRGIPass::IndirectFull);
    }
    double worst = 0.0;
    for (int frame = 0; frame < 3; ++frame)
    {
      first->Render();
      worst = std::max(worst, MaxDifference(fresh, mrgitest::GrabRGB(first)));
      second->Render();
      worst = std::max(worst, MaxDifference(fresh, mrgitest::GrabRGB(second)));
    }
    std::printf("two windows sharing actors: max difference to a window of its own %.0f\n", worst);
    MRGI_TEST_CHECK(firstPass->GetIndirectComputed() && secondPass->GetIndirectComputed());
    MRGI_TEST_CHECK(worst <= 1.0);
    firstPass->ReleaseGraphicsResources(first);
    secondPass->ReleaseGraphicsResources(second);
  }
  return 0;
}
