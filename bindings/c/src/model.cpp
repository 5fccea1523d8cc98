// Rig files and models (a mesh with its resolved rig).
#include "handles.hpp"

namespace {

using finflex::Error;
using finflex::ErrorCode;

finflex::BodyFrame from_c(const finflex_body_frame& frame) {
  finflex::BodyFrame out;
  for (int c = 0; c < 3; ++c) {
    out.origin[c] = frame.origin[c];
    out.axis_x[c] = frame.axis_x[c];
    out.axis_y[c] = frame.axis_y[c];
    out.axis_z[c] = frame.axis_z[c];
  }
  out.length = frame.length;
  return out;
}

finflex::BendMode bend_mode(finflex_bend_mode mode) {
  switch (mode) {
    case FINFLEX_BEND_PAPER:
      return finflex::BendMode::kPaper;
    case FINFLEX_BEND_EXACT:
      return finflex::BendMode::kExact;
    default:  // not a value of the enum: refused below
      break;
  }
  throw Error(ErrorCode::kInvalidArgument, "mode",
              "mode = " + std::to_string(static_cast<int>(mode)) +
                  ": expected FINFLEX_BEND_PAPER (0) or FINFLEX_BEND_EXACT (1)");
}

const finflex::RiggedMesh& model_of(const finflex_model* model) {
  return *finflex::c::require(model, "model")->model;
}

}  // namespace

using finflex::c::create;
using finflex::c::guarded;
using finflex::c::require;
using finflex::c::slot_of;

extern "C" {

finflex_status finflex_rig_load(const char* path, finflex_rig** rig) {
  return create(nullptr, rig, "rig", [&] {
    auto handle = std::make_unique<finflex_rig>();
    handle->spec = finflex::load_rig_file(require(path, "path"));
    return handle;
  });
}

finflex_status finflex_rig_parse(const char* json, finflex_rig** rig) {
  return create(nullptr, rig, "rig", [&] {
    auto handle = std::make_unique<finflex_rig>();
    handle->spec = finflex::parse_rig_json(require(json, "json"));
    return handle;
  });
}

void finflex_rig_destroy(finflex_rig* rig) { delete rig; }

const finflex_error* finflex_rig_error(const finflex_rig* rig) { return slot_of(rig); }

finflex_status finflex_model_create_single_bend(const finflex_mesh* mesh,
                                                const finflex_body_frame* frame,
                                                finflex_bend_mode mode, finflex_model** model) {
  return create(slot_of(mesh), model, "model", [&] {
    const finflex::Mesh& m = require(mesh, "mesh")->mesh;
    const finflex::BendMode parsed = bend_mode(mode);
    const finflex::BodyFrame body = frame == nullptr ? finflex::find_body_frame(m) : from_c(*frame);
    auto handle = std::make_unique<finflex_model>();
    handle->model = std::make_shared<const finflex::RiggedMesh>(
        finflex::RiggedMesh::single_bend(m, body, parsed));
    return handle;
  });
}

finflex_status finflex_model_create(const finflex_mesh* mesh, const finflex_rig* rig,
                                    finflex_model** model) {
  return create(slot_of(mesh), model, "model", [&] {
    const finflex::Mesh& m = require(mesh, "mesh")->mesh;
    const finflex::RigSpec& spec = require(rig, "rig")->spec;
    auto handle = std::make_unique<finflex_model>();
    handle->model = std::make_shared<const finflex::RiggedMesh>(m, finflex::resolve_rig(spec, m));
    return handle;
  });
}

void finflex_model_destroy(finflex_model* model) { delete model; }

const finflex_error* finflex_model_error(const finflex_model* model) { return slot_of(model); }

size_t finflex_model_vertex_count(const finflex_model* model) {
  return model == nullptr ? 0 : model->model->vertex_count();
}

size_t finflex_model_values_per_instance(const finflex_model* model) {
  return model == nullptr ? 0 : model->model->values_per_instance();
}

size_t finflex_model_parameter_count(const finflex_model* model) {
  return model == nullptr ? 0 : model->model->rig().parameters.size();
}

finflex_status finflex_model_parameter(finflex_model* model, size_t index,
                                       finflex_parameter_info* info) {
  return guarded(slot_of(model), [&] {
    const std::vector<finflex::RigParameter>& parameters = model_of(model).rig().parameters;
    require(info, "info");
    if (index >= parameters.size()) {
      throw Error(ErrorCode::kInvalidArgument, "index",
                  "index = " + std::to_string(index) + " is out of range: the model has " +
                      std::to_string(parameters.size()) + " parameters");
    }
    const finflex::RigParameter& p = parameters[index];
    info->name = p.name.c_str();
    info->offset = p.offset;
    info->count = p.count;
    info->limit = p.limit;
  });
}

finflex_status finflex_model_find_parameter(finflex_model* model, const char* name, size_t* index) {
  return guarded(slot_of(model), [&] {
    const finflex::Rig& rig = model_of(model).rig();
    const std::size_t found = rig.param_index(require(name, "name"));
    *require(index, "index") = found;
  });
}

}  // extern "C"
