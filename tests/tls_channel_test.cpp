// TLS on the bake channel, end to end: a real lightmass_server process with a
// certificate made at test time by the openssl command, and the client library.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <fstream>
#include <random>
#include <thread>

#include "editor_client/bake/bake_client.h"
#include "editor_client/bake/server_process.h"
#include "lightmass_server/net/server.h"
#include "protocol/channel_records.h"
#include "raw_client.h"
#include "test_paths.h"

namespace lc {
namespace {

using client::BakeClientOptions;
using client::ServerProcess;
namespace fs = std::filesystem;

const Guid kSceneGuid{7, 7, 7, 7};
const std::string kToken = "correct-horse-battery-staple";

std::string server_binary() {
    return (test::bin_dir() / "lightmass_server").string();
}

bool has(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

// Certificates for every test in this program, made once in a temporary directory.
struct Certificates {
    fs::path dir;
    fs::path cert, key;              // CN=localhost, SAN DNS:localhost, IP:127.0.0.1 (RSA 2048)
    fs::path stranger_cert;          // another self-signed certificate: the wrong CA
    fs::path other_cert, other_key;  // names only DNS:other
    fs::path token;
    std::string error;  // why they could not be made (openssl missing)
};

bool run(const std::string& command) {
    return std::system((command + " >/dev/null 2>&1").c_str()) == 0;
}

std::string self_signed(const fs::path& key, const fs::path& cert, const std::string& key_kind,
                        const std::string& name, const std::string& alt_names) {
    return "openssl req -x509 -newkey " + key_kind + " -nodes -keyout '" + key.string() + "' -out '" +
           cert.string() + "' -days 2 -subj /CN=" + name + " -addext subjectAltName=" + alt_names;
}

Certificates make_certificates() {
    Certificates c;
    if (!run("openssl version")) {
        c.error = "the openssl command is not installed: cannot make test certificates";
        return c;
    }
    c.dir = test::make_temp_dir("tls");
    c.cert = c.dir / "server.pem";
    c.key = c.dir / "server.key";
    c.stranger_cert = c.dir / "stranger.pem";
    c.other_cert = c.dir / "other.pem";
    c.other_key = c.dir / "other.key";
    c.token = c.dir / "token";
    const std::string ec = "ec -pkeyopt ec_paramgen_curve:prime256v1";
    if (!run(self_signed(c.key, c.cert, "rsa:2048", "localhost", "DNS:localhost,IP:127.0.0.1")) ||
        !run(self_signed(c.dir / "stranger.key", c.stranger_cert, ec, "stranger",
                         "DNS:localhost,IP:127.0.0.1")) ||
        !run(self_signed(c.other_key, c.other_cert, ec, "other", "DNS:other")))
        c.error = "openssl req failed to make a self-signed certificate in " + c.dir.string();
    std::ofstream(c.token) << kToken << "\n";
    return c;
}

const Certificates& certificates() {
    static const Certificates certs = make_certificates();
    return certs;
}

#define LC_REQUIRE_CERTIFICATES()                                                \
    do {                                                                         \
        if (!certificates().error.empty()) GTEST_SKIP() << certificates().error; \
    } while (0)

std::unique_ptr<ServerProcess> start_server(std::vector<std::string> extra) {
    std::vector<std::string> args = {"--quiet"};
    if (std::find(extra.begin(), extra.end(), "--listen") == extra.end()) {
        args.push_back("--listen");
        args.push_back("127.0.0.1:0");
    }
    args.insert(args.end(), extra.begin(), extra.end());
    auto server = ServerProcess::spawn_with(server_binary(), args);
    EXPECT_TRUE(server.ok()) << (server.ok() ? "" : server.error());
    return server.ok() ? std::move(server.value()) : nullptr;
}

std::unique_ptr<ServerProcess> start_tls_server(std::vector<std::string> extra = {}) {
    extra.insert(extra.end(),
                 {"--tls-cert", certificates().cert.string(), "--tls-key", certificates().key.string()});
    return start_server(extra);
}

std::string loopback(const ServerProcess& server) {
    return "127.0.0.1:" + std::to_string(test::port_of(server.address()));
}

BakeClientOptions plain_options(const ServerProcess& server) {
    BakeClientOptions options;
    options.server = loopback(server);
    options.timeout_seconds = 60.0;
    return options;
}

BakeClientOptions tls_options(const ServerProcess& server) {
    BakeClientOptions options = plain_options(server);
    options.tls = true;
    options.tls_ca_file = certificates().cert;
    return options;
}

SceneLight point_light(float x, float y, float z, float intensity, float range, uint32_t id) {
    SceneLight light;
    light.guid = Guid{0x2000u + id, 0, 0, id};
    light.type = LightType::kPoint;
    light.position = {x, y, z};
    light.intensity = intensity;
    light.range = range;
    return light;
}

std::vector<SceneLight> random_lights(size_t n, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> pos(-50.0f, 50.0f), power(1.0f, 100.0f);
    std::vector<SceneLight> lights;
    for (size_t i = 0; i < n; ++i)
        lights.push_back(
            point_light(pos(rng), pos(rng), pos(rng), power(rng), 0.0f, static_cast<uint32_t>(i)));
    return lights;
}

TEST(TlsChannel, TlsBakeDeliversTheSameTreeAsPlainTcp) {
    LC_REQUIRE_CERTIFICATES();
    auto tls_server = start_tls_server();
    auto plain_server = start_server({});
    ASSERT_TRUE(tls_server && plain_server);

    // The thesis's Figure 9.1 over TLS: root 27500, radius 700.
    std::vector<SceneLight> figure = {
        point_light(-300, 0, 150, 5000, 250, 0), point_light(-225, -45, 150, 7500, 250, 1),
        point_light(-300, 150, 150, 5000, 250, 2), point_light(0, 0, 150, 5000, 250, 3),
        point_light(150, 0, 150, 5000, 250, 4)};
    BakeClientOptions thesis = tls_options(*tls_server);
    thesis.representative_rule = RepresentativeRule::kThesisFirst;
    auto small = client::bake_lights(figure, kSceneGuid, thesis);
    ASSERT_TRUE(small.ok()) << small.error();
    ASSERT_EQ(small->tree.nodes.size(), 9u);
    EXPECT_FLOAT_EQ(small->tree.nodes[0].brightness, 27500.0f);
    EXPECT_NEAR(small->tree.nodes[0].radius, 700.0f, 1e-3);

    // 20,000 lights: a 1.4 MB scene channel up and a 3.6 MB result channel down,
    // several 1 MiB chunks each way, byte-identical to the plain-TCP bake.
    auto lights = random_lights(20000, 5);
    BakeClientOptions over_tls = tls_options(*tls_server);
    BakeClientOptions over_tcp = plain_options(*plain_server);
    for (BakeClientOptions* options : {&over_tls, &over_tcp}) {
        options->builder = BuilderKind::kLbvh;
        options->seed = 42;
    }
    auto secure = client::bake_lights(lights, kSceneGuid, over_tls);
    auto plain = client::bake_lights(lights, kSceneGuid, over_tcp);
    ASSERT_TRUE(secure.ok()) << secure.error();
    ASSERT_TRUE(plain.ok()) << plain.error();
    EXPECT_EQ(secure->tree.leaf_count, 20000u);
    EXPECT_EQ(secure->tree.nodes.size(), 39999u);
    EXPECT_GT(secure->result_channel.size(), 3u * 1024 * 1024);
    EXPECT_EQ(secure->result_channel, plain->result_channel);
    EXPECT_EQ(secure->result_channel_name, plain->result_channel_name);
    EXPECT_EQ(tls_server->terminate(), 0);
}

TEST(TlsChannel, HostNameWorksAsWellAsAddress) {
    LC_REQUIRE_CERTIFICATES();
    auto server = start_tls_server();
    ASSERT_TRUE(server);
    // "localhost": SNI is sent and the certificate's DNS name is checked.
    BakeClientOptions options = tls_options(*server);
    options.server = "localhost:" + std::to_string(test::port_of(server->address()));
    auto outcome = client::bake_lights(random_lights(10, 2), kSceneGuid, options);
    ASSERT_TRUE(outcome.ok()) << outcome.error();
    EXPECT_EQ(outcome->tree.nodes.size(), 19u);
}

TEST(TlsChannel, PlainClientIsRefusedClearlyAndServerKeepsServing) {
    LC_REQUIRE_CERTIFICATES();
    auto server = start_tls_server({"--threads", "2"});
    ASSERT_TRUE(server);
    // A silent peer holds a handshake open: it must not block anybody else.
    test::RawClient silent(test::port_of(server->address()), std::chrono::milliseconds(200));

    auto plain = client::bake_lights(random_lights(10, 3), kSceneGuid, plain_options(*server));
    ASSERT_FALSE(plain.ok());
    EXPECT_TRUE(has(plain.error(), "--tls")) << plain.error();
    EXPECT_TRUE(has(plain.error(), "TLS")) << plain.error();

    // Garbage that is neither TLS nor our framing.
    {
        test::RawClient garbage(test::port_of(server->address()));
        std::vector<uint8_t> bytes(300, 0xAB);
        garbage.send_bytes(bytes);
        EXPECT_TRUE(garbage.wait_closed());
    }

    auto after = client::bake_lights(random_lights(10, 3), kSceneGuid, tls_options(*server));
    ASSERT_TRUE(after.ok()) << after.error();
    EXPECT_EQ(after->tree.nodes.size(), 19u);
}

TEST(TlsChannel, SilentPeerIsDroppedAfterTheReadTimeout) {
    LC_REQUIRE_CERTIFICATES();
    auto server = start_tls_server({"--read-timeout-ms", "300"});
    ASSERT_TRUE(server);
    test::RawClient silent(test::port_of(server->address()), std::chrono::seconds(5));
    EXPECT_TRUE(silent.wait_closed()) << "a peer that never starts the TLS handshake must be dropped";
}

TEST(TlsChannel, UntrustedCertificateFailsVerification) {
    LC_REQUIRE_CERTIFICATES();
    auto server = start_tls_server();
    ASSERT_TRUE(server);
    const std::string expected =
        "TLS handshake with " + loopback(*server) + " failed: certificate verify failed";

    BakeClientOptions wrong_ca = tls_options(*server);
    wrong_ca.tls_ca_file = certificates().stranger_cert;
    auto refused = client::bake_lights(random_lights(5, 1), kSceneGuid, wrong_ca);
    ASSERT_FALSE(refused.ok());
    EXPECT_TRUE(has(refused.error(), expected)) << refused.error();
    EXPECT_TRUE(has(refused.error(), "self-signed certificate")) << refused.error();
    EXPECT_TRUE(has(refused.error(), "--tls-ca")) << refused.error();

    // Without --tls-ca the system's trust store is used, which does not know our certificate.
    BakeClientOptions system_ca = tls_options(*server);
    system_ca.tls_ca_file.clear();
    auto untrusted = client::bake_lights(random_lights(5, 1), kSceneGuid, system_ca);
    ASSERT_FALSE(untrusted.ok());
    EXPECT_TRUE(has(untrusted.error(), expected)) << untrusted.error();

    auto good = client::bake_lights(random_lights(5, 1), kSceneGuid, tls_options(*server));
    ASSERT_TRUE(good.ok()) << good.error();
}

TEST(TlsChannel, CertificateMustNameTheHost) {
    LC_REQUIRE_CERTIFICATES();
    auto server = start_server(
        {"--tls-cert", certificates().other_cert.string(), "--tls-key", certificates().other_key.string()});
    ASSERT_TRUE(server);
    BakeClientOptions by_address = tls_options(*server);
    by_address.tls_ca_file = certificates().other_cert;  // trusted, but it names "other"
    auto refused = client::bake_lights(random_lights(5, 1), kSceneGuid, by_address);
    ASSERT_FALSE(refused.ok());
    EXPECT_TRUE(has(refused.error(), "IP address mismatch")) << refused.error();

    BakeClientOptions by_name = by_address;
    by_name.server = "localhost:" + std::to_string(test::port_of(server->address()));
    auto refused_name = client::bake_lights(random_lights(5, 1), kSceneGuid, by_name);
    ASSERT_FALSE(refused_name.ok());
    EXPECT_TRUE(has(refused_name.error(), "hostname mismatch")) << refused_name.error();
}

TEST(TlsChannel, TlsClientAgainstPlainServerFailsClearly) {
    LC_REQUIRE_CERTIFICATES();
    auto server = start_server({});
    ASSERT_TRUE(server);
    auto outcome = client::bake_lights(random_lights(5, 1), kSceneGuid, tls_options(*server));
    ASSERT_FALSE(outcome.ok());
    EXPECT_TRUE(has(outcome.error(), "TLS handshake with " + loopback(*server) + " failed"))
        << outcome.error();
    EXPECT_TRUE(has(outcome.error(), "--tls-cert")) << outcome.error();
}

TEST(TlsChannel, CancelOverTlsStopsTheBake) {
    LC_REQUIRE_CERTIFICATES();
    auto server = start_tls_server();
    ASSERT_TRUE(server);
    // The Cancel frame is written while the client's read is pending: both
    // directions of the TLS stream in use at once.
    std::atomic<bool> cancel{false};
    BakeClientOptions options = tls_options(*server);
    options.builder = BuilderKind::kOptimalPair;
    options.pairing = PairingMode::kExact;
    options.cancel = &cancel;
    options.on_progress = [&](const ProgressMsg&) { cancel.store(true); };
    auto outcome = client::bake_lights(random_lights(6000, 4), kSceneGuid, options);
    ASSERT_FALSE(outcome.ok());
    EXPECT_EQ(outcome.error_kind(), ErrorKind::kCancelled) << outcome.error();

    auto after = client::bake_lights(random_lights(10, 4), kSceneGuid, tls_options(*server));
    ASSERT_TRUE(after.ok()) << after.error();
}

Result<tcp::endpoint> listen_with(const std::string& host, bool token, const fs::path& cert,
                                  const fs::path& key) {
    bake::ServerOptions options;
    options.host = host;
    if (token) options.token = kToken;
    options.tls_certificate = cert;
    options.tls_private_key = key;
    bake::Server server(options);
    return server.listen();
}

TEST(TlsChannel, OffLoopbackNeedsTokenAndTls) {
    LC_REQUIRE_CERTIFICATES();
    const Certificates& c = certificates();
    auto neither = listen_with("0.0.0.0", false, {}, {});
    ASSERT_FALSE(neither.ok());
    EXPECT_TRUE(
        has(neither.error(), "missing a token (--token-file FILE) and TLS (--tls-cert FILE --tls-key FILE)"))
        << neither.error();
    auto token_only = listen_with("0.0.0.0", true, {}, {});
    ASSERT_FALSE(token_only.ok());
    EXPECT_TRUE(has(token_only.error(), "missing TLS")) << token_only.error();
    EXPECT_FALSE(has(token_only.error(), "token (")) << token_only.error();
    auto tls_only = listen_with("0.0.0.0", false, c.cert, c.key);
    ASSERT_FALSE(tls_only.ok());
    EXPECT_TRUE(has(tls_only.error(), "missing a token")) << tls_only.error();
    EXPECT_FALSE(has(tls_only.error(), "TLS (")) << tls_only.error();

    // The program refuses the same way: it never reports an address.
    auto refused = ServerProcess::spawn_with(server_binary(),
                                             {"--listen", "0.0.0.0:0", "--token-file", c.token.string()});
    ASSERT_FALSE(refused.ok());
    EXPECT_TRUE(has(refused.error(), "did not report")) << refused.error();

    // With both it starts; a client reaches it over 127.0.0.1 with the token and TLS.
    auto server = start_tls_server({"--listen", "0.0.0.0:0", "--token-file", c.token.string()});
    ASSERT_TRUE(server);
    BakeClientOptions options = tls_options(*server);
    auto no_token = client::bake_lights(random_lights(3, 1), kSceneGuid, options);
    ASSERT_FALSE(no_token.ok());
    EXPECT_TRUE(has(no_token.error(), "token")) << no_token.error();
    options.token_file = c.token;
    auto outcome = client::bake_lights(random_lights(3, 1), kSceneGuid, options);
    ASSERT_TRUE(outcome.ok()) << outcome.error();
    EXPECT_EQ(outcome->tree.nodes.size(), 5u);
}

TEST(TlsChannel, BadTlsFilesAreRefusedAtStart) {
    LC_REQUIRE_CERTIFICATES();
    const Certificates& c = certificates();
    auto mismatched = listen_with("127.0.0.1", false, c.cert, c.other_key);
    ASSERT_FALSE(mismatched.ok());
    EXPECT_TRUE(has(mismatched.error(), "does not match")) << mismatched.error();
    auto missing = listen_with("127.0.0.1", false, c.dir / "absent.pem", c.key);
    ASSERT_FALSE(missing.ok());
    EXPECT_TRUE(has(missing.error(), "cannot read TLS certificate")) << missing.error();
    auto not_pem = listen_with("127.0.0.1", false, c.token, c.key);
    ASSERT_FALSE(not_pem.ok());
    EXPECT_TRUE(has(not_pem.error(), "PEM expected")) << not_pem.error();
    auto half = listen_with("127.0.0.1", false, c.cert, {});
    ASSERT_FALSE(half.ok());
    EXPECT_TRUE(has(half.error(), "--tls-key")) << half.error();

    BakeClientOptions client_side;
    client_side.server = "127.0.0.1:1";
    client_side.tls = true;
    client_side.tls_ca_file = c.token;
    auto bad_ca = client::bake_lights(random_lights(3, 1), kSceneGuid, client_side);
    ASSERT_FALSE(bad_ca.ok());
    EXPECT_TRUE(has(bad_ca.error(), "cannot load TLS CA file")) << bad_ca.error();
}

}  // namespace
}  // namespace lc
