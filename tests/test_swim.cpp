// Swimming (finflex/swim.hpp, finflex/cl_swim.hpp): the swim rig's binding, the
// device driver against the double-precision one, phases that integrate the
// frequency (no jump when the speed changes), a wave that travels from head to tail,
// and a whole frame (driver, then the deformation reading its buffers) against the
// reference.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <thread>

#include <gtest/gtest.h>

#include "finflex/finflex.hpp"
#include "finflex/internal/cl_tuning.hpp"
#include "support/deform.hpp"
#include "support/test_support.hpp"

namespace finflex {
namespace {

RiggedMesh load_model(const char* mesh_file, const char* rig_file) {
  const Mesh mesh = load_mesh(test::data_path(mesh_file));
  return RiggedMesh(mesh, resolve_rig(load_rig_file(test::data_path(rig_file)), mesh));
}

const RiggedMesh& barramundi() {
  static const RiggedMesh model =
      load_model("barramundi/BarramundiFish.gltf", "rigs/barramundi_swim.rig.json");
  return model;
}

// Fish i: cruising at 0.6 + 0.2 i body lengths per second, turning now and then.
std::vector<SwimInput> inputs_at(std::size_t fish, const std::vector<float>& lengths, int frame) {
  std::vector<SwimInput> inputs(fish);
  for (std::size_t i = 0; i < fish; ++i) {
    inputs[i].position = {0.3f * float(i), 0.5f, -0.2f * float(i)};
    inputs[i].yaw = 0.4f * float(i) + 0.01f * float(frame);
    inputs[i].pitch = 0.05f * float(i % 3) - 0.05f;
    inputs[i].speed = lengths[i] * (0.6f + 0.2f * float(i));
    inputs[i].turn_rate = (i % 2 ? 0.5f : -0.3f) * std::sin(0.1f * float(frame));
  }
  return inputs;
}

TEST(Swim, ASwimRigNeedsASpineOnItsBody) {
  try {
    SwimModel swim(load_model("barramundi/BarramundiFish.gltf", "rigs/barramundi.rig.json"));
    FAIL() << "a bend body is not a swim rig";
  } catch (const Error& e) {
    EXPECT_EQ(e.field(), "swim.wave");
    EXPECT_NE(std::string(e.what()).find("needs a body"), std::string::npos) << e.what();
  }
  SwimBinding binding;
  binding.tail = "body_wave";  // read by the spine, not a fin's hinge
  EXPECT_THROW(SwimModel(barramundi(), {}, binding), Error);
  SwimKinematics kinematics;
  kinematics.wavelength = 0.0;
  EXPECT_THROW(SwimModel(barramundi(), kinematics), Error);
  const SwimModel swim(barramundi());
  EXPECT_EQ(swim.samples(), 32u);
  EXPECT_NE(swim.tail_offset(), SwimModel::kNone);
  EXPECT_NE(swim.left_pectoral_offset(), SwimModel::kNone);
}

TEST(Swim, DeviceDriverMatchesTheReference) {
  const SwimModel swim(barramundi());
  const std::vector<float> lengths = {0.3f, 0.45f, 0.38f, 0.6f, 0.25f};
  const std::vector<float> phases = {0.0f, 0.3f, 0.7f, 0.1f, 0.95f};
  SwimReference reference(swim, lengths, phases);
  ClSwimDriver driver(test::shared_context(), swim, lengths, phases);
  const float dt = 1.0f / 30.0f;
  for (int frame = 0; frame < 40; ++frame) {
    const std::vector<SwimInput> inputs = inputs_at(lengths.size(), lengths, frame);
    reference.step(inputs, dt);
    driver.enqueue(inputs, dt);
  }
  const std::vector<float> device_phases = driver.read_wave_phases();
  const RigParameters device = driver.read_parameters();
  const std::vector<PlacementRecord> records = driver.read_placements();
  for (std::size_t i = 0; i < lengths.size(); ++i) {
    // 40 float additions of f dt: a few ulps of 1 each.
    EXPECT_NEAR(device_phases[i], reference.wave_phases()[i], 2e-5) << "fish " << i;
    for (std::size_t k = 0; k < device.values_per_instance(); ++k) {
      EXPECT_NEAR(device.values()[i * device.values_per_instance() + k],
                  reference.parameters().values()[i * device.values_per_instance() + k], 2e-4)
          << "fish " << i << " value " << k;
    }
    const PlacementRecord expected = placement_record(reference.placements()[i]);
    for (std::size_t k = 0; k < 13; ++k)
      EXPECT_NEAR(records[i][k], expected[k], 2e-5 * (1.0 + std::fabs(expected[k]))) << k;
  }
  EXPECT_EQ(driver.read_limited_segments(), reference.limited_segments());
}

// On CPUs one work-item drives a vector's worth of fish, one per lane, the lanes past
// the last fish repeating it (kernels/swim/driver.cl): 37 fish (more than two
// work-items, the last one partly filled) give what the reference and one fish per
// work-item (2 work-items per fish: never lanes) give, the spine's records included.
TEST(Swim, DriverWithAFishPerLaneMatchesOneFishPerWorkItem) {
  const SwimModel swim(barramundi());
  std::vector<float> lengths(37);
  for (std::size_t i = 0; i < lengths.size(); ++i) lengths[i] = 0.25f + 0.01f * float(i);
  SwimReference reference(swim, lengths);
  ClSwimDriver lanes(test::shared_context(), swim, lengths, {}, 1);
  ClSwimDriver items(test::shared_context(), swim, lengths, {}, 2);
  const float dt = 1.0f / 30.0f;
  for (int frame = 0; frame < 12; ++frame) {
    std::vector<SwimInput> inputs = inputs_at(lengths.size(), lengths, frame);
    for (std::size_t i = 0; i < inputs.size(); ++i)
      inputs[i].speed = lengths[i] * (0.5f + 0.05f * float(i));
    reference.step(inputs, dt);
    lanes.enqueue(inputs, dt);
    items.enqueue(inputs, dt);
  }
  const RigParameters a = lanes.read_parameters(), b = items.read_parameters();
  ASSERT_EQ(a.values().size(), reference.parameters().values().size());
  for (std::size_t k = 0; k < a.values().size(); ++k) {
    EXPECT_NEAR(a.values()[k], reference.parameters().values()[k], 2e-4) << "value " << k;
    EXPECT_NEAR(a.values()[k], b.values()[k], 1e-5) << "value " << k;
  }
  const std::vector<float> phases_a = lanes.read_wave_phases(), phases_b = items.read_wave_phases();
  const std::vector<PlacementRecord> placed_a = lanes.read_placements(),
                                     placed_b = items.read_placements();
  for (std::size_t i = 0; i < lengths.size(); ++i) {
    EXPECT_NEAR(phases_a[i], reference.wave_phases()[i], 2e-5) << "fish " << i;
    EXPECT_EQ(phases_a[i], phases_b[i]) << "fish " << i;
    const PlacementRecord expected = placement_record(reference.placements()[i]);
    for (std::size_t k = 0; k < 13; ++k) {
      EXPECT_NEAR(placed_a[i][k], expected[k], 2e-5 * (1.0 + std::fabs(expected[k])))
          << "fish " << i << " value " << k;
    }
  }
  EXPECT_EQ(lanes.read_limited_segments(), reference.limited_segments());
  EXPECT_EQ(items.read_limited_segments(), reference.limited_segments());
  ASSERT_NE(lanes.derived_buffer(), nullptr);
  const std::size_t floats = lengths.size() * 8 * swim.samples();
  std::vector<float> records_a(floats), records_b(floats);
  cl::CommandQueue& queue = test::shared_context().queue();
  queue.enqueueReadBuffer(*lanes.derived_buffer(), CL_TRUE, 0, floats * sizeof(float),
                          records_a.data());
  queue.enqueueReadBuffer(*items.derived_buffer(), CL_TRUE, 0, floats * sizeof(float),
                          records_b.data());
  for (std::size_t k = 0; k < floats; ++k)
    ASSERT_NEAR(records_a[k], records_b[k], 2e-5) << "fish " << k / (8 * swim.samples());
}

// Inputs written straight into the upload's staging memory (staged_inputs, then
// enqueue_staged) drive the fish to the same bits as a copy of them (enqueue), over more
// frames than the staging ring has areas, with copied frames in between on the same
// driver, and the area asked for twice in a frame.
TEST(Swim, StagedInputsDriveAsCopiedOnes) {
  const SwimModel swim(barramundi());
  std::vector<float> lengths(37);
  for (std::size_t i = 0; i < lengths.size(); ++i) lengths[i] = 0.25f + 0.01f * float(i);
  ClSwimDriver copied(test::shared_context(), swim, lengths);
  ClSwimDriver staged(test::shared_context(), swim, lengths);
  const float dt = 1.0f / 30.0f;
  for (int frame = 0; frame < 11; ++frame) {
    const std::vector<SwimInput> inputs = inputs_at(lengths.size(), lengths, frame);
    copied.enqueue(inputs, dt);
    if (frame % 4 == 3) {
      staged.staged_inputs();  // taken, then overwritten by a copied frame
      staged.enqueue(inputs, dt);
    } else {
      SwimInput* area = staged.staged_inputs();
      ASSERT_NE(area, nullptr);
      std::copy(inputs.begin(), inputs.end(), area);
      ASSERT_EQ(staged.staged_inputs(), area) << "the same area until it is enqueued";
      staged.enqueue_staged(dt);
    }
    // Every frame: a frame's parameters and placements come from its own inputs.
    ASSERT_EQ(staged.read_parameters().values(), copied.read_parameters().values()) << frame;
    ASSERT_EQ(staged.read_wave_phases(), copied.read_wave_phases()) << frame;
    const std::vector<PlacementRecord> a = staged.read_placements(), b = copied.read_placements();
    for (std::size_t i = 0; i < lengths.size(); ++i) {
      for (std::size_t k = 0; k < 13; ++k)  // the records' 13 used floats
        ASSERT_EQ(a[i][k], b[i][k]) << "frame " << frame << " fish " << i;
    }
    ASSERT_EQ(staged.read_limited_segments(), copied.read_limited_segments()) << frame;
  }
}

// A bad staged value is named as enqueue names it; nothing runs, and the inputs stay
// staged to be mended. Enqueueing with nothing staged is refused by name.
TEST(Swim, BadStagedInputsAreNamedAndStayStaged) {
  const SwimModel swim(barramundi());
  const std::vector<float> lengths = {0.4f, 0.3f};
  ClSwimDriver driver(test::shared_context(), swim, lengths);
  auto field_of = [&](float dt) {
    try {
      driver.enqueue_staged(dt);
    } catch (const Error& e) {
      return e.field();
    }
    return std::string("accepted");
  };
  EXPECT_EQ(field_of(0.1f), "staged_inputs");
  const std::vector<float> before = driver.read_wave_phases();
  SwimInput* area = driver.staged_inputs();
  const std::vector<SwimInput> inputs = inputs_at(lengths.size(), lengths, 0);
  std::copy(inputs.begin(), inputs.end(), area);
  area[1].speed = -1.0f;
  EXPECT_EQ(field_of(0.1f), "inputs[1].speed");
  area[1].speed = 0.2f;
  area[0].yaw = NAN;
  EXPECT_EQ(field_of(0.1f), "inputs[0].yaw");
  area[0].yaw = 0.0f;
  EXPECT_EQ(field_of(0.0f), "dt");
  EXPECT_EQ(field_of(NAN), "dt");
  EXPECT_EQ(driver.read_wave_phases(), before) << "a refused frame ran";
  EXPECT_EQ(driver.staged_inputs(), area);
  EXPECT_EQ(field_of(0.1f), "accepted");
  EXPECT_NE(driver.read_wave_phases(), before);
  EXPECT_EQ(field_of(0.1f), "staged_inputs") << "an enqueued area is staged again";
}

// The driver shares a spine's samples out over a work-group of 64 on GPUs (one
// work-item per fish on CPUs) and clears folding segment by segment with a scan
// (kernels/swim/driver.cl): both on every device, a table of 150 samples (3 per
// work-item), fish turning hard enough for segments to be limited.
TEST(Swim, DeviceDriverMatchesTheReferenceWithLongTablesAndLimitedSegments) {
  const Mesh mesh = load_mesh(test::data_path("barramundi/BarramundiFish.gltf"));
  RigSpec spec = load_rig_file(test::data_path("rigs/barramundi_swim.rig.json"));
  set_option(spec.components.front().chain.front(), "samples", 150.0);
  const RiggedMesh model(mesh, resolve_rig(spec, mesh));
  SwimKinematics sharp;
  sharp.max_turn_curvature = 40.0;  // turning radii far below the body's thickness
  const SwimModel swim(model, sharp);
  ASSERT_EQ(swim.samples(), 150u);
  const std::vector<float> lengths = {0.3f, 0.45f, 0.38f, 0.6f};
  const float dt = 1.0f / 30.0f;
  std::vector<SwimInput> inputs = inputs_at(lengths.size(), lengths, 0);
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    inputs[i].speed = 3.0f * lengths[i];
    inputs[i].turn_rate = i % 2 ? 40.0f : -40.0f;
  }
  SwimReference reference(swim, lengths);
  reference.step(inputs, dt);
  EXPECT_GT(reference.limited_segments(), 0u);
  for (std::size_t items : {1u, 2u, 8u, 32u, 64u}) {
    SCOPED_TRACE("work-items per fish " + std::to_string(items));
    ClSwimDriver driver(test::shared_context(), swim, lengths, {}, items);
    driver.enqueue(inputs, dt);
    EXPECT_EQ(driver.read_limited_segments(), reference.limited_segments());
    const RigParameters device = driver.read_parameters();
    for (std::size_t k = 0; k < device.values().size(); ++k)
      EXPECT_NEAR(device.values()[k], reference.parameters().values()[k], 2e-4) << "value " << k;
  }
  EXPECT_THROW(ClSwimDriver(test::shared_context(), swim, lengths, {}, 5), Error);
  EXPECT_THROW(ClSwimDriver(test::shared_context(), swim, lengths, {}, 128), Error);
}

TEST(Swim, PhasesIntegrateTheFrequencyWithoutJumps) {
  const SwimModel swim(barramundi());
  const std::vector<float> lengths = {0.4f};
  SwimReference fish(swim, lengths);
  std::vector<SwimInput> input(1);
  const double dt = 0.01;
  double previous = 0.0;
  for (int frame = 0; frame < 400; ++frame) {
    input[0].speed = frame < 200 ? 0.2f : 1.0f;  // 0.5 then 2.5 body lengths per second
    fish.step(input, dt);
    const double advanced = std::fmod(fish.wave_phases()[0] - previous + 1.0, 1.0);
    // Each step advances by this step's frequency times dt: continuous, never back.
    EXPECT_NEAR(advanced, fish.frequencies()[0] * dt, 1e-12) << "frame " << frame;
    previous = fish.wave_phases()[0];
  }
  // Webb et al. 1984: f = 3.19 L_cm^(-1/3) + 1.29 U / L.
  EXPECT_NEAR(fish.frequencies()[0], 3.19 / std::cbrt(40.0) + 1.29 * 2.5, 1e-6);  // 0.4f, 1.0f
}

// The midline's lateral offset at the samples, from the spine's angles (Z of the spine).
std::vector<double> midline(const SwimModel& swim, const float* theta) {
  std::vector<double> z(swim.samples(), 0.0);
  for (std::size_t k = 1; k < z.size(); ++k)
    z[k] = z[k - 1] + swim.spacing() * std::sin(0.5 * (theta[k] + theta[k - 1]));
  return z;
}

TEST(Swim, TheWaveTravelsFromHeadToTail) {
  const SwimModel swim(barramundi());
  const std::vector<float> lengths = {0.4f};
  SwimReference fish(swim, lengths);
  std::vector<SwimInput> input(1);
  input[0].speed = 0.4f;
  fish.step(input, 0.01);
  const std::size_t wave = swim.wave_offset();
  const std::vector<double> before = midline(swim, fish.parameters().values().data() + wave);
  fish.step(input, 0.02);
  const std::vector<double> after = midline(swim, fish.parameters().values().data() + wave);
  // The shift of the pattern along the body that best maps `before` onto `after`:
  // samples run from the tail (k = 0) to the snout, so tailward is negative k.
  double best = 1e300;
  int best_shift = 0;
  for (int shift = -4; shift <= 4; ++shift) {
    double error = 0.0;
    for (int k = 8; k + 8 < int(after.size()); ++k) {
      // Compare slopes (the rigid offset of the pivot drops out).
      const double a = after[std::size_t(k + 1)] - after[std::size_t(k)];
      const double b = before[std::size_t(k + 1 - shift)] - before[std::size_t(k - shift)];
      error += (a - b) * (a - b);
    }
    if (error < best) {
      best = error;
      best_shift = shift;
    }
  }
  EXPECT_LT(best_shift, 0) << "the wave must move towards the tail";
}

TEST(Swim, AFrameFromTheDeviceDriverMatchesTheReference) {
  const SwimModel swim(barramundi());
  const std::vector<float> lengths = {0.3f, 0.45f, 0.38f};
  SwimReference reference(swim, lengths);
  ClSwimDriver driver(test::shared_context(), swim, lengths);
  ClDeformer deformer(test::shared_context(), swim.model());
  DeviceBatch batch = deformer.allocate(lengths.size());
  for (int frame = 0; frame < 5; ++frame) {
    const std::vector<SwimInput> inputs = inputs_at(lengths.size(), lengths, frame);
    reference.step(inputs, 1.0 / 30.0);
    driver.enqueue(inputs, 1.0f / 30.0f);
  }
  for (NormalMode normals : {NormalMode::kRotate, NormalMode::kJacobian}) {
    ClJob job;
    job.instances = lengths.size();
    job.device.parameters = &driver.parameter_buffer();
    job.device.placements = &driver.placement_buffer();
    job.normals = normals;
    job.outputs = &batch;
    deformer.enqueue(job);
    const DeformedBatch<float> device = deformer.read(batch);
    // The reference deforms with the device driver's own values (float), so that only
    // the deformation is compared here (the drivers are compared above).
    const RigParameters values = driver.read_parameters();
    const DeformedBatch<double> expected =
        run_reference(swim.model(), values, normals, false, reference.placements().data());
    const AccuracyReport report = compare_to_reference(swim.model(), values.view(), normals, device,
                                                       expected, reference.placements().data());
    EXPECT_LE(report.max_position_ratio, 1.0) << report.max_position_error;
    EXPECT_LE(report.max_normal_ratio, 1.0) << report.max_normal_error;
  }
}

// The driver writes the spine's records itself (ClSwimDriver::derived_buffer): the
// frame skips rig_prepare and deforms to the same bits as with rig_prepare summing in
// the same order (one work-item per fish, 16 or 64), on every device. A derived buffer
// that does not fit is refused by name.
TEST(Swim, DriverPreparedRecordsDeformAsRigPrepareDoes) {
  const SwimModel swim(barramundi());
  const std::vector<float> lengths = {0.3f, 0.45f, 0.38f, 0.5f};
  for (std::size_t items : {1u, 16u, 64u}) {
    SCOPED_TRACE("work-items per fish " + std::to_string(items));
    ClSwimDriver driver(test::shared_context(), swim, lengths, {}, items);
    ASSERT_NE(driver.derived_buffer(), nullptr);
    ClTuning options;  // rig_prepare sums in the same order as the driver
    options.table_items = items;
    ClDeformer deformer(test::shared_context(), swim.model(), options);
    DeviceBatch prepared = deformer.allocate(lengths.size());
    DeviceBatch by_rig_prepare = deformer.allocate(lengths.size());
    ClJob job;
    job.instances = lengths.size();
    job.device.parameters = &driver.parameter_buffer();
    job.device.placements = &driver.placement_buffer();
    for (int frame = 0; frame < 4; ++frame) {
      driver.enqueue(inputs_at(lengths.size(), lengths, frame), 1.0f / 30.0f);
      job.device.derived = driver.derived_buffer();
      job.outputs = &prepared;
      deformer.enqueue(job);
      job.device.derived = nullptr;
      job.outputs = &by_rig_prepare;
      deformer.enqueue(job);
      const DeformedBatch<float> a = deformer.read(prepared), b = deformer.read(by_rig_prepare);
      ASSERT_EQ(a.positions, b.positions) << "frame " << frame;
      ASSERT_EQ(a.normals, b.normals) << "frame " << frame;
    }
    job.outputs = &prepared;
    job.instances = lengths.size() + 1;  // more than the buffer holds
    job.device.derived = driver.derived_buffer();
    DeviceBatch larger = deformer.allocate(lengths.size() + 1);
    job.outputs = &larger;
    try {
      deformer.enqueue(job);
      FAIL() << "expected an error naming job.device.derived";
    } catch (const Error& e) {
      EXPECT_EQ(e.field(), "job.device.derived") << e.what();
    }
  }
  // A model without derived values takes none.
  const RiggedMesh bend = RiggedMesh::single_bend(
      barramundi().mesh(), find_body_frame(barramundi().mesh()), BendMode::kPaper);
  ClDeformer bend_deformer(test::shared_context(), bend);
  EXPECT_EQ(bend_deformer.derived_floats_per_instance(), 0u);
  EXPECT_EQ(ClDeformer(test::shared_context(), swim.model()).derived_floats_per_instance(),
            8u * swim.samples());
}

// A frame behind a FrameGate: nothing of it runs until the gate opens, then it gives
// what the same frame without a gate gives; a gate left closed opens as it goes.
TEST(Swim, AFrameBehindAGateRunsWhenTheGateOpens) {
  const SwimModel swim(barramundi());
  const std::vector<float> lengths = {0.3f, 0.45f, 0.38f};
  const std::vector<SwimInput> inputs = inputs_at(lengths.size(), lengths, 3);
  ClSwimDriver open_driver(test::shared_context(), swim, lengths);
  open_driver.enqueue(inputs, 1.0f / 30.0f);
  const RigParameters expected = open_driver.read_parameters();

  // Two drivers behind one gate (two species of a tank): the second one's first
  // enqueue sets up its staging memory while the first one's upload waits.
  ClSwimDriver gated(test::shared_context(), swim, lengths);
  ClSwimDriver second(test::shared_context(), swim, lengths);
  {
    FrameGate gate(test::shared_context());
    EXPECT_FALSE(gate.is_open());
    const cl::Event driven = gated.enqueue(inputs, 1.0f / 30.0f, gate.wait_list());
    const cl::Event driven_second = second.enqueue(inputs, 1.0f / 30.0f, gate.wait_list());
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    EXPECT_NE(driven.getInfo<CL_EVENT_COMMAND_EXECUTION_STATUS>(), CL_COMPLETE);
    EXPECT_NE(driven_second.getInfo<CL_EVENT_COMMAND_EXECUTION_STATUS>(), CL_COMPLETE);
    gate.open();
    gate.open();  // once is enough
    EXPECT_TRUE(gate.is_open());
    ASSERT_EQ(driven_second.wait(), CL_SUCCESS);
  }
  EXPECT_EQ(gated.read_parameters().values(), expected.values());
  EXPECT_EQ(second.read_parameters().values(), expected.values());

  ClSwimDriver left_closed(test::shared_context(), swim, lengths);
  {
    FrameGate gate(test::shared_context());
    left_closed.enqueue(inputs, 1.0f / 30.0f, gate.wait_list());
  }  // not opened: the destructor does
  EXPECT_EQ(left_closed.read_parameters().values(), expected.values());
}

TEST(Swim, AContextWaitsForItsQueuesAndOpensAGateThatOutlivesIt) {
  const SwimModel swim(barramundi());
  const std::vector<float> lengths = {0.3f, 0.45f, 0.38f};
  const std::vector<SwimInput> inputs = inputs_at(lengths.size(), lengths, 3);
  auto context = std::make_unique<Context>();
  std::unique_ptr<FrameGate> gate;
  cl::Event driven;
  {
    ClSwimDriver driver(*context, swim, lengths);
    gate = std::make_unique<FrameGate>(*context);
    driven = driver.enqueue(inputs, 1.0f / 30.0f, gate->wait_list());
  }  // the driver goes, its frame still behind the gate
  EXPECT_NE(driven.getInfo<CL_EVENT_COMMAND_EXECUTION_STATUS>(), CL_COMPLETE);
  context.reset();  // opens the gate, then waits for the frame
  EXPECT_EQ(driven.getInfo<CL_EVENT_COMMAND_EXECUTION_STATUS>(), CL_COMPLETE);
  EXPECT_NO_THROW(gate->open());  // already opened: nothing left to do
  gate.reset();
}

// Frame after frame, each gate is a new event of its own (a reused, complete one would
// let its frame run at once), and frames gated one after the other give the frames of an
// ungated driver.
TEST(Swim, GatesFrameAfterFrameEachHoldTheirOwnFrame) {
  const SwimModel swim(barramundi());
  const std::vector<float> lengths = {0.3f, 0.45f, 0.38f};
  auto context = std::make_unique<Context>();
  ClSwimDriver ungated(*context, swim, lengths);
  auto gated = std::make_unique<ClSwimDriver>(*context, swim, lengths);
  std::vector<cl::Event> gate_events;  // held, so that no handle is freed and made again
  for (int frame = 0; frame < 20; ++frame) {
    const std::vector<SwimInput> inputs = inputs_at(lengths.size(), lengths, frame);
    ungated.enqueue(inputs, 1.0f / 30.0f);
    FrameGate gate(*context);
    gate_events.push_back(gate.wait_list()->front());
    const cl::Event driven = gated->enqueue(inputs, 1.0f / 30.0f, gate.wait_list());
    if (frame % 5 == 0) {  // held back until the gate opens (a few frames: each waits)
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
      EXPECT_NE(driven.getInfo<CL_EVENT_COMMAND_EXECUTION_STATUS>(), CL_COMPLETE)
          << "frame " << frame;
    }
    gate.open();
  }
  std::vector<cl_event> handles;
  for (const cl::Event& event : gate_events) handles.push_back(event());
  std::sort(handles.begin(), handles.end());
  EXPECT_EQ(std::adjacent_find(handles.begin(), handles.end()), handles.end())
      << "a user event served two gates";
  EXPECT_EQ(gated->read_wave_phases(), ungated.read_wave_phases());
  EXPECT_EQ(gated->read_parameters().values(), ungated.read_parameters().values());
  {
    FrameGate gate(*context);
    gated->enqueue(inputs_at(lengths.size(), lengths, 20), 1.0f / 30.0f, gate.wait_list());
    gate.open();
  }
  gated.reset();
  context.reset();
}

// The inputs' check goes over blocks of 4 fish with SSE2 (copied inputs), of 8 with
// AVX2 (staged inputs, where the processor has it), then fish one by one:
// a bad value is found wherever it lies, through enqueue() and enqueue_staged().
TEST(Swim, EveryBadInputIsFoundWhereverItLies) {
  const SwimModel swim(barramundi());
  const std::vector<float> lengths(13, 0.3f);  // 3 blocks of 4 fish, and one after
  ClSwimDriver driver(test::shared_context(), swim, lengths);
  // Every value of the good inputs >= 0: the fast check then passes them, and a bad speed
  // it misses would be accepted (a value it flags wrongly only sends the inputs to the
  // check that names the problem).
  std::vector<SwimInput> good = inputs_at(lengths.size(), lengths, 2);
  for (SwimInput& input : good) {
    for (std::size_t f = 0; f < 7; ++f) {
      float& value = reinterpret_cast<float*>(&input)[f];
      value = std::fabs(value);
    }
  }
  auto field_of = [&](const std::vector<SwimInput>& inputs) {
    std::string copied = "accepted", staged = "accepted";
    try {
      driver.enqueue(inputs, 0.1f);
    } catch (const Error& e) {
      copied = e.field();
    }
    SwimInput* area = driver.staged_inputs();
    std::copy(inputs.begin(), inputs.end(), area);
    try {
      driver.enqueue_staged(0.1f);
    } catch (const Error& e) {
      staged = e.field();
    }
    EXPECT_EQ(copied, staged);
    return copied;
  };
  for (std::size_t i = 0; i < lengths.size(); ++i) {
    const std::string fish = "inputs[" + std::to_string(i) + "]";
    std::vector<SwimInput> inputs = good;
    for (std::size_t f = 0; f < 7; ++f) {
      inputs = good;
      reinterpret_cast<float*>(&inputs[i])[f] = NAN;
      EXPECT_EQ(field_of(inputs).rfind(fish + ".", 0), 0u) << fish << " float " << f;
    }
    inputs = good;
    inputs[i].speed = -std::numeric_limits<float>::denorm_min();
    EXPECT_EQ(field_of(inputs), fish + ".speed");
    inputs[i].speed = -0.0f;
    inputs[i].turn_rate = -1.0f;  // other values may be negative
    inputs[i].yaw = -3.0f;
    EXPECT_EQ(field_of(inputs), "accepted") << fish;
  }
}

TEST(Swim, BadInputsAreNamed) {
  const SwimModel swim(barramundi());
  SwimReference fish(swim, {0.4f, 0.3f});
  ClSwimDriver driver(test::shared_context(), swim, {0.4f, 0.3f});
  auto field_of = [&](const std::vector<SwimInput>& inputs, double dt) {
    std::string reference_field = "accepted", device_field = "accepted";
    try {
      fish.step(inputs, dt);
    } catch (const Error& e) {
      reference_field = e.field();
    }
    try {
      driver.enqueue(inputs, float(dt));
    } catch (const Error& e) {
      device_field = e.field();
    }
    EXPECT_EQ(reference_field, device_field);
    return reference_field;
  };
  std::vector<SwimInput> inputs(2);
  EXPECT_EQ(field_of(inputs, 0.0), "dt");
  EXPECT_EQ(field_of(inputs, NAN), "dt");
  EXPECT_EQ(field_of(std::vector<SwimInput>(3), 0.1), "inputs");
  inputs[1].speed = -1.0f;
  EXPECT_EQ(field_of(inputs, 0.1), "inputs[1].speed");
  inputs[1].speed = 0.0f;
  inputs[0].turn_rate = INFINITY;
  EXPECT_EQ(field_of(inputs, 0.1), "inputs[0].turn_rate");
  inputs[0].turn_rate = 0.0f;
  EXPECT_EQ(field_of(inputs, 0.1), "accepted");
  // The device's check reads the bits: -0 is a speed of 0, the smallest negative
  // subnormal is below 0, a NaN anywhere is named.
  inputs[1].speed = -0.0f;
  EXPECT_EQ(field_of(inputs, 0.1), "accepted");
  inputs[1].speed = -std::numeric_limits<float>::denorm_min();
  EXPECT_EQ(field_of(inputs, 0.1), "inputs[1].speed");
  inputs[1].speed = NAN;
  EXPECT_EQ(field_of(inputs, 0.1), "inputs[1].speed");
  inputs[1].speed = 0.5f;
  inputs[1].position.y = -INFINITY;
  EXPECT_NE(field_of(inputs, 0.1).find("inputs[1].position"), std::string::npos);
  inputs[1].position.y = 0.0f;
  EXPECT_EQ(field_of(inputs, 0.1), "accepted");
  // The largest finite values pass; a NaN with its sign bit set does not.
  inputs[0].position.x = std::numeric_limits<float>::max();
  inputs[0].position.z = -std::numeric_limits<float>::max();
  EXPECT_EQ(field_of(inputs, 0.1), "accepted");
  inputs[0].pitch = -std::numeric_limits<float>::quiet_NaN();
  EXPECT_EQ(field_of(inputs, 0.1), "inputs[0].pitch");
  EXPECT_THROW(SwimReference(swim, {0.4f, 0.0f}), Error);
  EXPECT_THROW(ClSwimDriver(test::shared_context(), swim, {NAN}), Error);
  // More fish than the kernel's 32-bit indices reach (256 floats of spine records a
  // fish): refused before anything is allocated.
  ASSERT_EQ(8u * swim.samples(), 256u);
  try {
    ClSwimDriver(test::shared_context(), swim, std::vector<float>(8388608, 0.3f));
    FAIL() << "expected an error naming lengths";
  } catch (const Error& e) {
    EXPECT_EQ(e.field(), "lengths") << e.what();
    EXPECT_NE(std::string(e.what()).find("8388607"), std::string::npos) << e.what();
  }
  EXPECT_THROW(SwimReference(swim, {}), Error);
}

}  // namespace
}  // namespace finflex
