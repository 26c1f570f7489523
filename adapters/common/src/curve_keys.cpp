#include "cosim/link/curve_keys.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#include <yaml-cpp/yaml.h>
#include <zmq.h>

#include <cerrno>
#include <cstring>
#include <sstream>
#include <stdexcept>

#include "cosim/util/errors.h"

namespace cosim::link {

namespace fs = std::filesystem;

namespace {

const char kZ85[] =
    "0123456789abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ.-:+=^!/*?&<>()[]{}@%$#";

// Writes `text` to a new file `file` (mode 0600); `replace`: an existing file is removed first.
void writePrivateFile(const fs::path& file, const std::string& text, bool replace) {
  if (replace) ::unlink(file.c_str());
  const int fd = ::open(file.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0600);
  if (fd < 0) {
    const int err = errno;
    throw Error(err == EEXIST ? ErrorKind::input : kindOfErrno(err),
                "cannot create the key file " + file.string() + ": " + std::strerror(err) +
                    (err == EEXIST ? " (it exists; cosim never replaces a key file)" : ""));
  }
  const bool ok = ::fchmod(fd, 0600) == 0 &&
                  ::write(fd, text.data(), text.size()) == static_cast<ssize_t>(text.size());
  const int err = errno;
  ::close(fd);
  if (!ok) {
    ::unlink(file.c_str());
    throw Error(kindOfErrno(err),
                "cannot write the key file " + file.string() + ": " + std::strerror(err));
  }
}

// The YAML map in a key file, after checking that only its owner may read it.
YAML::Node readPrivateYaml(const fs::path& file, const std::string& what, const std::string& fix) {
  struct stat st {};
  if (::stat(file.c_str(), &st) != 0) {
    const int err = errno;
    throw Error(kindOfErrno(err),
                what + " " + file.string() + ": " + std::strerror(err) + "; " + fix);
  }
  if ((st.st_mode & 077) != 0) {
    std::ostringstream mode;
    mode << std::oct << (st.st_mode & 0777);
    throw InputError(what + " " + file.string() + " has mode 0" + mode.str() +
                     ": others may read its secret key; make it private with 'chmod 600 " +
                     file.string() + "' (or replace the key if others have read it)");
  }
  YAML::Node node;
  try {
    node = YAML::LoadFile(file.string());
  } catch (const std::exception& e) {
    throw InputError(what + " " + file.string() + " is not a cosim key file (" + e.what() + "); " +
                     fix);
  }
  if (!node.IsMap())
    throw InputError(what + " " + file.string() + " is not a cosim key file; " + fix);
  return node;
}

std::string keyIn(const YAML::Node& node, const char* key, const fs::path& file,
                  const std::string& what, const std::string& fix) {
  std::string value;
  if (node[key] && node[key].IsScalar()) value = node[key].as<std::string>();
  if (!isZ85Key(value)) {
    throw InputError(what + " " + file.string() + ": '" + key +
                     "' is missing or not a 40-character Z85 key; " + fix);
  }
  return value;
}

std::string emitted(const std::string& comment,
                    const std::vector<std::pair<std::string, std::string>>& entries) {
  YAML::Emitter em;
  em << YAML::Comment(comment) << YAML::Newline << YAML::BeginMap;
  for (const auto& [k, v] : entries) em << YAML::Key << k << YAML::Value << YAML::DoubleQuoted << v;
  em << YAML::EndMap;
  return std::string(em.c_str()) + "\n";
}

}  // namespace

bool curveAvailable() { return zmq_has("curve") != 0; }

void requireCurve() {
  if (!curveAvailable()) {
    throw ResourceError(
        "this libzmq cannot encrypt (zmq_has(\"curve\") is false: built without libsodium); "
        "install a libzmq with CurveZMQ (Debian's libzmq5 has it), or, on a network you trust, "
        "set transport.insecure: true");
  }
}

CurveKeyPair newCurveKeyPair() {
  requireCurve();
  char pub[41] = {0}, sec[41] = {0};
  if (zmq_curve_keypair(pub, sec) != 0)
    throw ResourceError(std::string("cannot make a CurveZMQ key pair: ") +
                        zmq_strerror(zmq_errno()));
  CurveKeyPair pair{pub, sec};
  std::memset(sec, 0, sizeof sec);
  return pair;
}

bool isZ85Key(const std::string& key) {
  return key.size() == 40 && key.find_first_not_of(kZ85) == std::string::npos;
}

CurveKeyPair readKeyPairFile(const fs::path& file) {
  const std::string what = "the orchestrator's key file";
  const std::string fix = "create one with 'cosim keys' (or name another in transport.key_file)";
  const YAML::Node node = readPrivateYaml(file, what, fix);
  return {keyIn(node, "public_key", file, what, fix), keyIn(node, "secret_key", file, what, fix)};
}

void writeKeyPairFile(const fs::path& file, const CurveKeyPair& pair) {
  if (file.has_parent_path()) {
    std::error_code ec;
    fs::create_directories(file.parent_path(), ec);
    if (!ec) fs::permissions(file.parent_path(), fs::perms::owner_all, ec);
  }
  writePrivateFile(file,
                   emitted("cosim: the orchestrator's CurveZMQ key pair (cosim keys). Keep it "
                           "private (mode 0600): whoever has the secret key can pose as your "
                           "orchestrator.",
                           {{"public_key", pair.public_key}, {"secret_key", pair.secret_key}}),
                   false);
}

void writeParticipantKeyFile(const fs::path& file, const CurveClientKeys& keys,
                             const std::string& run_id, const std::string& participant) {
  writePrivateFile(
      file,
      emitted("cosim: the CurveZMQ keys of participant '" + participant + "' of run " + run_id +
                  ", valid for this run only. Hand it to the participant with --key-file (copy "
                  "it with scp, keep it mode 0600, delete it after the run).",
              {{"run_id", run_id},
               {"participant", participant},
               {"orchestrator_public_key", keys.orchestrator_public},
               {"public_key", keys.own.public_key},
               {"secret_key", keys.own.secret_key}}),
      true);
}

ParticipantKeyFile readParticipantKeyFile(const fs::path& file) {
  const std::string what = "--key-file";
  const std::string fix =
      "cosim writes a participant's key file into the run folder (.cosim-NAME.key) when it "
      "starts a run over tcp:// with a participant of launch: external";
  const YAML::Node node = readPrivateYaml(file, what, fix);
  ParticipantKeyFile out;
  if (node["run_id"]) out.run_id = node["run_id"].as<std::string>("");
  if (node["participant"]) out.participant = node["participant"].as<std::string>("");
  out.keys.orchestrator_public = keyIn(node, "orchestrator_public_key", file, what, fix);
  out.keys.own = {keyIn(node, "public_key", file, what, fix),
                  keyIn(node, "secret_key", file, what, fix)};
  return out;
}

std::string curveKeysVariableText(const CurveClientKeys& keys) {
  return keys.orchestrator_public + " " + keys.own.public_key + " " + keys.own.secret_key;
}

CurveClientKeys parseCurveKeysVariable(const std::string& text) {
  std::istringstream in(text);
  CurveClientKeys k;
  std::string extra;
  in >> k.orchestrator_public >> k.own.public_key >> k.own.secret_key >> extra;
  if (!isZ85Key(k.orchestrator_public) || !isZ85Key(k.own.public_key) ||
      !isZ85Key(k.own.secret_key) || !extra.empty()) {
    throw InputError(std::string("the environment variable ") + kCurveKeysVariable +
                     " is not three 40-character Z85 keys (orchestrator public, "
                     "participant public, participant secret); cosim sets it for the "
                     "participants it starts: unset it, or use --key-file");
  }
  return k;
}

}  // namespace cosim::link
