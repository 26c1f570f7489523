#include "keys_command.h"

#include <yaml-cpp/yaml.h>

#include <ostream>

#include "cosim/link/curve_keys.h"
#include "link_security.h"

namespace cosim::orchestrator {

namespace fs = std::filesystem;

namespace {

bool isParticipantKeyFile(const fs::path& file) {
  try {
    const YAML::Node n = YAML::LoadFile(file.string());
    return n.IsMap() && n["orchestrator_public_key"];
  } catch (const std::exception&) {
    return false;  // readKeyPairFile says what is wrong with it
  }
}

void howParticipantsGetKeys(std::ostream& out) {
  out << "\nA run over tcp:// (transport.bind) encrypts its link with this key pair and issues "
         "every participant\nkeys of its own, valid for that run only. cosim hands them to the "
         "participants it starts itself\nthrough the environment (never the command line). For "
         "a participant of launch: external it writes\nthem to RUN/.cosim-NAME.key (mode 0600, "
         "removed at the end of the run) and prints how to start it:\n  ADAPTER --endpoint "
         "tcp://HOST:PORT --name NAME ... --token-file RUN/.cosim-run-token --key-file "
         "RUN/.cosim-NAME.key\nOn a node that does not share the run folder, copy both files "
         "there first (scp -p keeps the mode).\nThe secret keys are never printed: `cosim keys "
         "FILE` shows the public keys of any key file.\n";
}

}  // namespace

int keysCommand(const fs::path& given, std::ostream& out) {
  const fs::path file = given.empty() ? defaultKeyFile() : given;
  if (fs::exists(file) && isParticipantKeyFile(file)) {
    const link::ParticipantKeyFile k = link::readParticipantKeyFile(file);
    out << "participant key file " << file.string() << " (mode 0600)\n"
        << "  run:                     " << k.run_id << "\n"
        << "  participant:             " << k.participant << "\n"
        << "  public key:              " << k.keys.own.public_key << "\n"
        << "  orchestrator public key: " << k.keys.orchestrator_public << "\n"
        << "  secret key:              (in the file, not shown)\n"
        << "Start the participant with --key-file " << file.string()
        << " (and the run's --token-file).\n";
    return 0;
  }
  bool created = false;
  if (!fs::exists(fs::symlink_status(file))) {
    link::writeKeyPairFile(file, link::newCurveKeyPair());
    created = true;
  }
  const link::CurveKeyPair pair = link::readKeyPairFile(file);
  out << (created ? "created" : "existing") << " orchestrator key file " << file.string()
      << " (mode 0600)\n"
      << "  public key: " << pair.public_key << "\n"
      << "  secret key: (in the file, not shown)\n"
      << (given.empty()
              ? "tcp:// runs use it unless transport.key_file names another.\n"
              : "Name it in the scenario: transport: { key_file: " + file.string() + " }\n");
  howParticipantsGetKeys(out);
  return 0;
}

}  // namespace cosim::orchestrator
