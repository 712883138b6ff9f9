#pragma once
// The bond models a case can choose. Each model is a type with the same
// static interface (compute_strain, compute_forces, particle_strain_energy,
// uses_rotation); the time step is written once as a template over it.
#include <string>

#include "kernels/paper_model.hpp"
#include "src/types.hpp"

namespace mpsolid {

enum class ModelKind { paper };

inline ModelKind model_kind(const std::string& name) {
  if (name == "paper") return ModelKind::paper;
  throw InputError("unknown model '" + name + "'");
}

// Calls f(Model{}) with the model type selected at run time; the whole time
// loop is instantiated per model, so the dispatch happens once per call.
template <class F>
decltype(auto) with_model(ModelKind kind, F&& f) {
  switch (kind) {
    case ModelKind::paper:
      break;
  }
  return f(PaperModel{});
}

}  // namespace mpsolid
