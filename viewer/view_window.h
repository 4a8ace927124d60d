#pragma once
// `kerf view`'s window (VTK's render window and interactor): the body's
// surface moved by its displacement and coloured by von Mises stress, the
// session stepped between frames for as long as a frame allows, the frame
// rate and the physics rate shown. The left mouse button drags the blade
// over the body (the scene's first live cut); with Ctrl it turns the camera
// (right: zoom, middle: pan).
#include <memory>
#include <optional>
#include <string>

#include <vtkActor.h>
#include <vtkDataSetSurfaceFilter.h>
#include <vtkInteractorStyle.h>
#include <vtkNew.h>
#include <vtkPolyDataMapper.h>
#include <vtkRenderWindow.h>
#include <vtkRenderWindowInteractor.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>
#include <vtkTextActor.h>

#include "app/session.h"
#include "viewer/blade_input.h"
#include "viewer/body_surface.h"

namespace kerf {

struct ViewOptions {
  int width = 900, height = 700;  // pixels
  std::optional<Index> blade_cut;  // the live cut the mouse feeds
  double blade_depth = 0.0;        // m behind the picked point; 0: 0.4 of the body's diagonal
  double frame_budget_s = 0.012;   // stepping time a frame
};

class ViewWindow {
 public:
  ViewWindow(Session& session, const ViewOptions& options);
  ~ViewWindow();
  /// Steps between frames until the window is closed.
  void interact();
  /// The session stepped `steps` times (fewer when it is done), then drawn.
  void step(int steps);
  /// The mouse at (x, y) pixels from the lower left: pressed, moved or released (as the interactor reports it).
  void press(int x, int y);
  void move(int x, int y);
  void release(int x, int y);
  /// A step failed: the window says why and steps no more (the session wrote it in its summary).
  void stop(const std::string& why);
  /// The window as it is drawn, to a PNG file.
  void screenshot(const std::string& path);
  int width() const { return options_.width; }
  int height() const { return options_.height; }

 private:
  class Style;
  void draw();
  void on_timer();
  void cut_at(int x, int y);
  std::string status_text() const;

  Session& session_;
  ViewOptions options_;
  std::unique_ptr<BodySurface> surface_;
  std::unique_ptr<BladeInput> blade_;
  Index pieces_drawn_ = 0;
  vtkNew<vtkRenderer> renderer_;
  vtkNew<vtkRenderWindow> window_;
  vtkNew<vtkRenderWindowInteractor> interactor_;
  vtkNew<vtkDataSetSurfaceFilter> faces_;
  vtkNew<vtkPolyDataMapper> mapper_;
  vtkNew<vtkActor> actor_;
  vtkSmartPointer<vtkInteractorStyle> style_;
  vtkNew<vtkTextActor> text_;
  double frames_per_s_ = 0.0, steps_per_s_ = 0.0, last_frame_ = 0.0, mises_max_ = 0.0;
  std::string stopped_;  // why the stepping stopped
};

}  // namespace kerf
