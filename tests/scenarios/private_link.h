// A network namespace with a private link (a veth pair) to this one, for the tests that put
// participants on "another host": this side HOST, the other side PEER (10.213.N.1 and .2 of a
// /30). Needs root and iproute2 (`ip`); `why` says why it could not be made. The link can be cut
// and restored: its end on this side is set down, after which packets between the two sides
// are silently lost (no reset, no error the other side could see) while every address stays,
// as when a cable or switch between two hosts fails. Removed again when the test ends.
#pragma once

#include <unistd.h>

#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace cosim::test {

struct PrivateLink {
  std::string ns, host, peer, veth;
  std::string why;  // why it could not be made; empty when it was

  explicit PrivateLink(int n) {
    ns = "cosim-t" + std::to_string(getpid()) + "-" + std::to_string(n % 1000);
    veth = "cosv" + std::to_string(getpid() % 100000) + "-" + std::to_string(n % 100);
    host = "10.213." + std::to_string(n % 250) + ".1";
    peer = "10.213." + std::to_string(n % 250) + ".2";
    const std::string steps =
        "ip netns add " + ns + " && ip link add " + veth + "a type veth peer name " + veth +
        "b && ip link set " + veth + "b netns " + ns + " && ip addr add " + host + "/30 dev " +
        veth + "a && ip link set " + veth + "a up && ip netns exec " + ns + " ip addr add " + peer +
        "/30 dev " + veth + "b && ip netns exec " + ns + " ip link set " + veth +
        "b up && ip netns exec " + ns + " ip link set lo up";
    why = run(steps);
    if (!why.empty())
      why = "cannot make a network namespace with a private link (needs root and iproute2): " + why;
  }
  ~PrivateLink() {
    std::system(
        ("ip link del " + veth + "a 2>/dev/null; ip netns del " + ns + " 2>/dev/null").c_str());
  }
  PrivateLink(const PrivateLink&) = delete;
  PrivateLink& operator=(const PrivateLink&) = delete;

  // Cuts the link (this side's end down) and restores it; empty, or why it failed.
  std::string cut() const { return run("ip link set " + veth + "a down"); }
  std::string restore() const { return run("ip link set " + veth + "a up"); }

 private:
  // Runs `command` with sh; empty when it succeeded, else its error output.
  static std::string run(const std::string& command) {
    const std::filesystem::path err =
        std::filesystem::temp_directory_path() /
        ("cosim-netns-" + std::to_string(getpid()) + "-" + std::to_string(++calls()) + ".err");
    const int rc = std::system(("(" + command + ") 2>" + err.string()).c_str());
    std::ifstream in(err);
    std::stringstream s;
    s << in.rdbuf();
    std::filesystem::remove(err);
    if (rc == 0) return "";
    return s.str().empty() ? "'" + command + "' failed" : s.str();
  }
  static std::atomic<int>& calls() {
    static std::atomic<int> n{0};
    return n;
  }
};

}  // namespace cosim::test
