#include "viewer/view_window.h"

#include <algorithm>
#include <cstdio>

#include <vtkCallbackCommand.h>
#include <vtkCamera.h>
#include <vtkCell.h>
#include <vtkCellPicker.h>
#include <vtkInteractorStyleTrackballCamera.h>
#include <vtkLookupTable.h>
#include <vtkObjectFactory.h>
#include <vtkPNGWriter.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkProperty.h>
#include <vtkTextProperty.h>
#include <vtkWindowToImageFilter.h>

#include "core/timer.h"

namespace kerf {

/// The left button drags the blade; with Ctrl, and the other buttons, the camera moves as in ParaView.
class ViewWindow::Style : public vtkInteractorStyleTrackballCamera {
 public:
  static Style* New();
  vtkTypeMacro(Style, vtkInteractorStyleTrackballCamera);
  ViewWindow* owner = nullptr;

  void OnLeftButtonDown() override {
    if (Interactor->GetControlKey() || !owner->blade_) return vtkInteractorStyleTrackballCamera::OnLeftButtonDown();
    cutting_ = true;
    owner->cut_at(Interactor->GetEventPosition()[0], Interactor->GetEventPosition()[1]);
  }
  void OnMouseMove() override {
    if (!cutting_) return vtkInteractorStyleTrackballCamera::OnMouseMove();
    owner->cut_at(Interactor->GetEventPosition()[0], Interactor->GetEventPosition()[1]);
  }
  void OnLeftButtonUp() override {
    if (!cutting_) return vtkInteractorStyleTrackballCamera::OnLeftButtonUp();
    cutting_ = false;
  }

 private:
  bool cutting_ = false;
};
vtkStandardNewMacro(ViewWindow::Style);

namespace {

double diagonal_of(const BodySnapshot& body) {
  Vec3 low = Vec3::Constant(1e300), high = -low;
  for (const Vec3& p : body.points) low = low.cwiseMin(p), high = high.cwiseMax(p);
  return (high - low).norm();
}

/// A frame of the interactive loop. A failure (a diverging step) cannot go up through VTK's event loop: the
/// window shows it and the session, which wrote it in its summary, takes no more steps.
void on_timer_event(vtkObject*, unsigned long, void* window, void*) {
  auto* view = static_cast<ViewWindow*>(window);
  try {
    view->step(0);
  } catch (const std::exception& e) {
    view->stop(e.what());
  }
}

}  // namespace

ViewWindow::ViewWindow(Session& session, const ViewOptions& options) : session_(session), options_(options) {
  const BodySnapshot body = session_.snapshot();
  surface_ = std::make_unique<BodySurface>(body);
  if (options_.blade_cut) {
    const double diagonal = diagonal_of(body);
    const double depth = options_.blade_depth > 0.0 ? options_.blade_depth : 0.4 * diagonal;
    blade_ = std::make_unique<BladeInput>(session_, *options_.blade_cut, 0.2 * diagonal, depth, 0.004 * diagonal);
  }
  faces_->SetInputData(surface_->grid());
  mapper_->SetInputConnection(faces_->GetOutputPort());
  mapper_->SetScalarModeToUsePointFieldData();
  mapper_->SelectColorArray("von_mises");
  vtkNew<vtkLookupTable> colours;  // blue (no stress) to red (the largest now)
  colours->SetHueRange(0.667, 0.0);
  colours->Build();
  mapper_->SetLookupTable(colours);
  actor_->SetMapper(mapper_);
  actor_->GetProperty()->SetSpecular(0.0);  // no highlight as white as the background
  renderer_->AddActor(actor_);
  renderer_->SetBackground(1.0, 1.0, 1.0);
  text_->GetTextProperty()->SetColor(0.0, 0.0, 0.0);
  text_->GetTextProperty()->SetFontSize(14);
  text_->SetPosition(8, 8);
  renderer_->AddActor2D(text_);
  window_->AddRenderer(renderer_);
  window_->SetSize(options_.width, options_.height);
  window_->SetWindowName("kerf view");
  interactor_->SetRenderWindow(window_);
  auto style = vtkSmartPointer<Style>::New();
  style->owner = this;
  style_ = style;
  interactor_->SetInteractorStyle(style_);
  // Seen from the front (-y), z up, as a body hangs or sags.
  vtkCamera* camera = renderer_->GetActiveCamera();
  camera->SetPosition(0, -1, 0);
  camera->SetFocalPoint(0, 0, 0);
  camera->SetViewUp(0, 0, 1);
  draw();
  renderer_->ResetCamera();
  window_->Render();
  last_frame_ = now_seconds();
}

ViewWindow::~ViewWindow() = default;

void ViewWindow::interact() {
  interactor_->Initialize();
  vtkNew<vtkCallbackCommand> timer;
  timer->SetCallback(on_timer_event);
  timer->SetClientData(this);
  interactor_->AddObserver(vtkCommand::TimerEvent, timer);
  interactor_->CreateRepeatingTimer(16);
  interactor_->Start();
}

void ViewWindow::stop(const std::string& why) {
  stopped_ = why;
  text_->SetInput(status_text().c_str());
  window_->Render();
}

void ViewWindow::step(int steps) {
  if (!stopped_.empty()) return;
  const double start = now_seconds();
  int taken = 0;
  // steps = 0: as many as the frame's budget allows (the timer's frames).
  while (!session_.done() && (steps > 0 ? taken < steps : now_seconds() - start < options_.frame_budget_s)) {
    session_.step();
    ++taken;
  }
  const double now = now_seconds(), elapsed = std::max(now - last_frame_, 1e-9);
  frames_per_s_ = 0.8 * frames_per_s_ + 0.2 / elapsed;
  steps_per_s_ = 0.8 * steps_per_s_ + 0.2 * taken / elapsed;
  last_frame_ = now;
  draw();
}

void ViewWindow::draw() {
  surface_->update(session_.snapshot());
  if (blade_ && blade_->cut().piece_count() > pieces_drawn_) {
    surface_->cut_by(blade_->cut(), pieces_drawn_);
    pieces_drawn_ = blade_->cut().piece_count();
  }
  surface_->grid()->Modified();
  faces_->Update();
  double range[2] = {0.0, 1.0};
  surface_->grid()->GetPointData()->GetArray("von_mises")->GetRange(range);
  mises_max_ = std::max(range[1], 1e-12);
  mapper_->SetScalarRange(0.0, mises_max_);
  text_->SetInput(status_text().c_str());
  window_->Render();
}

std::string ViewWindow::status_text() const {
  char line[256];
  const double real_time = steps_per_s_ * session_.time_step();
  std::snprintf(line, sizeof line, "t = %.3f s   %.1f frames/s   physics %.0f steps/s (%.2fx real time)%s",
                session_.time(), frames_per_s_, steps_per_s_, real_time, session_.done() ? "   (end of the scene)" : "");
  std::string text = line;
  std::snprintf(line, sizeof line, "\nvon Mises stress: blue 0 to red %.4g Pa", mises_max_);
  text += line;
  if (!blade_)
    text += "\nno live cut in the scene (cuts[i].live): the mouse moves the camera";
  else
    text += "\nblade: " + std::to_string(blade_->positions()) + " positions (left drag; Ctrl+left turns the camera)";
  if (blade_ && !blade_->refusal().empty()) text += "\nrefused: " + blade_->refusal();
  if (!stopped_.empty()) text += "\nstopped: " + stopped_;
  return text;
}

void ViewWindow::cut_at(int x, int y) {
  vtkNew<vtkCellPicker> picker;
  picker->SetTolerance(0.0005);
  if (!picker->Pick(x, y, 0.0, renderer_) || picker->GetActor() != actor_.GetPointer()) return;  // off the body
  vtkPolyData* faces = faces_->GetOutput();
  vtkCell* cell = faces->GetCell(picker->GetCellId());
  std::vector<double> weights(static_cast<std::size_t>(cell->GetNumberOfPoints()));
  cell->InterpolateFunctions(picker->GetPCoords(), weights.data());
  vtkDataArray* reference = faces->GetPointData()->GetArray(BodySurface::reference_array);
  Vec3 picked = Vec3::Zero();
  for (vtkIdType k = 0; k < cell->GetNumberOfPoints(); ++k) {
    double r[3];
    reference->GetTuple(cell->GetPointId(k), r);
    picked += weights[k] * Vec3(r[0], r[1], r[2]);
  }
  double sight[3];
  renderer_->GetActiveCamera()->GetDirectionOfProjection(sight);
  if (blade_->move_to(picked, Vec3(sight[0], sight[1], sight[2]).normalized())) draw();
}

void ViewWindow::press(int x, int y) {
  interactor_->SetEventInformation(x, y, 0, 0);
  interactor_->InvokeEvent(vtkCommand::LeftButtonPressEvent, nullptr);
}

void ViewWindow::move(int x, int y) {
  interactor_->SetEventInformation(x, y, 0, 0);
  interactor_->InvokeEvent(vtkCommand::MouseMoveEvent, nullptr);
}

void ViewWindow::release(int x, int y) {
  interactor_->SetEventInformation(x, y, 0, 0);
  interactor_->InvokeEvent(vtkCommand::LeftButtonReleaseEvent, nullptr);
}

void ViewWindow::screenshot(const std::string& path) {
  window_->Render();
  vtkNew<vtkWindowToImageFilter> image;
  image->SetInput(window_);
  image->ReadFrontBufferOff();
  image->Update();
  vtkNew<vtkPNGWriter> writer;
  writer->SetFileName(path.c_str());
  writer->SetInputConnection(image->GetOutputPort());
  writer->Write();
}

}  // namespace kerf
