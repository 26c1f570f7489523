// Writes one serialised message of every kind the protocol has, as a participant or the
// orchestrator of the settling-sphere scene would send it, into the folder given: the seeds of
// fuzz_protocol (scripts/fuzz.sh) and of the replay test of the decoder
// (tests/orchestrator/protocol_test.cpp).
//   fuzz_protocol_seeds FOLDER
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "cosim.pb.h"
#include "cosim/link/fields.h"
#include "cosim/link/particle_data.h"
#include "cosim/link/particle_wire.h"
#include "cosim/link/transport.h"

namespace fs = std::filesystem;
using namespace cosim;

namespace {

wire::Envelope withHeader(std::uint64_t step) {
  wire::Envelope e;
  auto* h = e.mutable_header();
  h->set_protocol_version(wire::PROTOCOL_VERSION);
  h->set_run_id("0f3ad114");
  h->set_participant("particles");
  h->set_step(step);
  h->set_time(1e-4 * static_cast<double>(step));
  h->set_token("65fccc7265fccc7265fccc7265fccc72");
  return e;
}

link::ParticleData particles(std::initializer_list<const char*> names) {
  link::ParticleData d;
  d.ids = {1, 2, 7};
  for (const char* n : names) {
    auto& v = d.field(n);
    for (std::size_t i = 0; i < v.size(); ++i) v[i] = 1e-3 * static_cast<double>(i + 1);
  }
  return d;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: fuzz_protocol_seeds FOLDER\n");
    return 2;
  }
  const fs::path out = argv[1];
  fs::create_directories(out);
  auto write = [&](const std::string& name, const wire::Envelope& e) {
    std::ofstream(out / (name + ".bin"), std::ios::binary) << link::serialize(e);
  };

  auto hello = withHeader(0);
  auto* h = hello.mutable_hello();
  h->set_role(wire::PARTICLES);
  h->set_adapter("free-particles");
  for (const char* f : {field::position, field::velocity, field::radius}) h->add_provides(f);
  for (const char* f : {field::drag_coefficient, field::fluid_velocity}) h->add_accepts(f);
  h->set_pid(4242);
  h->set_host("node1");
  write("hello", hello);

  auto welcome = withHeader(0);
  auto* w = welcome.mutable_welcome();
  w->add_send(field::position);
  w->add_receive(field::drag_coefficient);
  w->set_config_yaml("particles: [ { id: 1, position: [0, 0, 0], radius: 2.5e-5 } ]\n");
  w->set_workdir("/tmp/run/particles");
  w->set_cfd_dt(1e-4);
  w->set_dem_steps(10);
  w->set_end_time(5e-3);
  (*w->mutable_parameters())["d"] = 5e-5;
  write("welcome", welcome);

  auto refused = withHeader(0);
  refused.mutable_refused()->set_reason("protocol version 2 but the orchestrator speaks 3");
  write("refused", refused);

  auto sample = withHeader(3);
  cosim::link::toWire(particles({field::position, field::radius, field::velocity}),
                      *sample.mutable_sample()->mutable_particles());
  write("sample", sample);

  auto samples = withHeader(3);
  cosim::link::toWire(particles({field::fluid_velocity, field::voidage, field::pressure_gradient}),
                      *samples.mutable_samples()->mutable_at_particles());
  samples.mutable_samples()->add_lost_ids(7);
  samples.mutable_samples()->set_wall_seconds(0.002);
  write("samples", samples);

  auto advance = withHeader(4);
  advance.mutable_advance()->set_dt(1e-4);
  advance.mutable_advance()->set_substeps(10);
  cosim::link::toWire(particles({field::drag_coefficient, field::fluid_velocity,
                                 field::explicit_force, field::coating_increment}),
                      *advance.mutable_advance()->mutable_terms());
  write("advance", advance);

  auto advanced = withHeader(4);
  auto* a = advanced.mutable_advanced();
  cosim::link::toWire(
      particles({field::position, field::velocity, field::radius, field::coating_mass}),
      *a->mutable_state());
  a->add_inserted_ids(9);
  a->add_deleted_ids(2);
  a->set_wall_seconds(0.01);
  a->mutable_particles();
  write("advanced-particles", advanced);

  auto fluid = withHeader(4);
  auto* f = fluid.mutable_advanced();
  cosim::link::toWire(particles({field::precursor_removed}), *f->mutable_state());
  auto* report = f->mutable_fluid();
  report->set_pressure_drop(120.5);
  report->set_max_courant(0.3);
  report->mutable_species()->set_precursor_in(1e-9);
  write("advanced-fluid", fluid);

  auto checkpoint = withHeader(5);
  checkpoint.mutable_checkpoint()->set_path("/tmp/run/checkpoints/0.0005/particles");
  write("checkpoint", checkpoint);

  auto written = withHeader(5);
  written.mutable_checkpoint_written()->add_files("restart.liggghts");
  write("checkpoint-written", written);

  auto shutdown = withHeader(6);
  shutdown.mutable_shutdown()->set_reason("end of run");
  write("shutdown", shutdown);

  auto goodbye = withHeader(6);
  goodbye.mutable_goodbye()->set_message("done");
  write("goodbye", goodbye);

  auto error = withHeader(6);
  error.mutable_error()->set_message("LIGGGHTS: lost atoms");
  error.mutable_error()->set_where("advance");
  write("error", error);

  auto heartbeat = withHeader(6);
  heartbeat.mutable_heartbeat()->set_sequence(17);
  write("heartbeat", heartbeat);
  return 0;
}
