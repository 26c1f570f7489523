// CurveZMQ keys: the key pairs that encrypt and authenticate a tcp:// link, and the files that
// hold them. The orchestrator has a long-term key pair (its key file, written by `cosim keys`);
// every run issues each participant a fresh key pair and accepts no other (transport.h, Hub).
// A participant learns its keys and the orchestrator's public key from a participant key file
// (--key-file, for participants of launch: external) or from the environment variable
// COSIM_CURVE_KEYS (set by cosim for the participants it starts). Keys are Z85 text, 40
// characters; a secret key is never printed or logged. C++17.
#pragma once

#include <filesystem>
#include <string>

namespace cosim::link {

// The environment variable through which cosim hands a participant it starts its keys:
// "ORCHESTRATOR_PUBLIC PARTICIPANT_PUBLIC PARTICIPANT_SECRET" (never on the command line).
inline constexpr const char* kCurveKeysVariable = "COSIM_CURVE_KEYS";

// True when this libzmq can do CurveZMQ (zmq_has("curve"): built with libsodium).
bool curveAvailable();
// Throws std::runtime_error saying what to do when it cannot.
void requireCurve();

struct CurveKeyPair {
  std::string public_key;  // Z85, 40 characters
  std::string secret_key;  // Z85, 40 characters; never printed
};

// A fresh key pair from libzmq (the kernel's random source through libsodium).
CurveKeyPair newCurveKeyPair();

// True for 40 characters of the Z85 alphabet.
bool isZ85Key(const std::string& key);

// What a participant needs to connect over CurveZMQ. Empty: a plain connection (ipc://, or tcp://
// with transport.insecure).
struct CurveClientKeys {
  std::string orchestrator_public;  // the server's public key
  CurveKeyPair own;
  bool empty() const { return orchestrator_public.empty(); }
};

// The orchestrator's key file: a YAML map with public_key and secret_key, mode 0600.
// Reading refuses a missing or malformed file, or one that others may read, with the path and
// what to do (`cosim keys`). Writing creates the file (and its folder, mode 0700) and never
// replaces an existing one.
CurveKeyPair readKeyPairFile(const std::filesystem::path& file);
void writeKeyPairFile(const std::filesystem::path& file, const CurveKeyPair& pair);

// A participant key file (mode 0600): which run and participant it is for, the orchestrator's
// public key and the participant's key pair. An existing file is replaced (an earlier run's).
void writeParticipantKeyFile(const std::filesystem::path& file, const CurveClientKeys& keys,
                             const std::string& run_id, const std::string& participant);
struct ParticipantKeyFile {
  std::string run_id, participant;
  CurveClientKeys keys;
};
ParticipantKeyFile readParticipantKeyFile(const std::filesystem::path& file);

// COSIM_CURVE_KEYS: the text of the variable, and back (std::runtime_error if malformed).
std::string curveKeysVariableText(const CurveClientKeys& keys);
CurveClientKeys parseCurveKeysVariable(const std::string& text);

}  // namespace cosim::link
