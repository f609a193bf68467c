// SPDX-License-Identifier: MIT
// Captures the errors and warnings a VTK object reports, instead of letting VTK print them
// (the library never prints): VTK hands a message to an ErrorEvent/WarningEvent
// observer when the reporting object has one, and prints only otherwise.
#pragma once

#include <vtkCallbackCommand.h>
#include <vtkCommand.h>
#include <vtkNew.h>
#include <vtkObject.h>

#include <string>

namespace frictopt::io::detail {

class VtkErrorCapture {
 public:
  /// Observes `object` (must outlive this capture) from now on.
  explicit VtkErrorCapture(vtkObject* object) {
    callback_->SetClientData(this);
    callback_->SetCallback(&VtkErrorCapture::on_event);
    object->AddObserver(vtkCommand::ErrorEvent, callback_);
    object->AddObserver(vtkCommand::WarningEvent, callback_);
  }

  [[nodiscard]] bool has_error() const { return !errors_.empty(); }
  /// All error messages so far, joined by "; " (empty if none).
  [[nodiscard]] const std::string& errors() const { return errors_; }

 private:
  static void on_event(vtkObject*, unsigned long event, void* client, void* call_data) {
    auto* self = static_cast<VtkErrorCapture*>(client);
    if (event != vtkCommand::ErrorEvent) return;  // warnings are dropped, errors decide
    std::string message = call_data != nullptr ? static_cast<const char*>(call_data) : "";
    while (!message.empty() && (message.back() == '\n' || message.back() == ' '))
      message.pop_back();
    if (!self->errors_.empty()) self->errors_ += "; ";
    self->errors_ += message;
  }

  vtkNew<vtkCallbackCommand> callback_;
  std::string errors_;
};

}  // namespace frictopt::io::detail
