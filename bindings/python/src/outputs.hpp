// Deformed instances on the host, as numpy arrays of shape (instances, vertices, 3) in
// mesh vertex order: views of the planes (finflex/batch.hpp) without a copy.
#pragma once

#include <memory>
#include <optional>
#include <variant>

#include <nanobind/ndarray.h>

#include "bindings.hpp"

namespace finflex::python {

// (instances, vertices, 3) float32 or float64, a view.
using Array3 = nb::ndarray<nb::numpy, nb::shape<-1, -1, 3>>;

class Outputs {
 public:
  // `batch` as read from a device (float32) or computed by the reference (float64).
  // A batch over slots (a rig's reordering) is put into mesh order once, here.
  Outputs(DeformedBatch<float> batch, std::shared_ptr<const RiggedMesh> model);
  Outputs(DeformedBatch<double> batch, std::shared_ptr<const RiggedMesh> model);

  const BatchShape& shape() const;
  // The attribute's values, owned by `self` (this object's Python handle).
  Array3 positions(nb::handle self) const;
  Array3 normals(nb::handle self) const;
  std::optional<Array3> tangents(nb::handle self) const;            // none when the mesh has none
  std::optional<Array3> previous_positions(nb::handle self) const;  // none when not written
  // The rest mesh with this instance's positions, normals and tangents.
  Mesh instance_mesh(std::size_t instance) const;

 private:
  std::variant<DeformedBatch<float>, DeformedBatch<double>> batch_;
  std::shared_ptr<const RiggedMesh> model_;

  Array3 view(nb::handle self, int attribute) const;
};

}  // namespace finflex::python
