// jaus-console --plugin: the console knows a plugin's kinds, and the page is
// told what to show of them (welcome `views`), as it is of built-in kinds. The
// real program on loopback (its page on 127.0.0.141:8080, its own state
// folder); a plugin it cannot load is bad usage, said before anything starts.
#include <utility>  // Boost 1.74's Asio headers need it first

#include <gtest/gtest.h>

#include <boost/asio/connect.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/websocket.hpp>
#include <chrono>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "../../system/child_process.hpp"

namespace {

namespace asio = boost::asio;
namespace beast = boost::beast;
namespace fs = std::filesystem;
using tcp = asio::ip::tcp;

fs::path fresh_folder(const std::string& name) {
  const fs::path folder = fs::temp_directory_path() / (name + "-" + std::to_string(::getpid()));
  fs::remove_all(folder);
  fs::create_directories(folder);
  return folder;
}

constexpr const char* kPageHost = "127.0.0.141";
constexpr std::uint16_t kPagePort = 8080;

// The page's first frames up to the welcome (the console sends it first on a new page).
std::optional<nlohmann::json> welcome_from_page() {
  asio::io_context io;
  beast::websocket::stream<tcp::socket> ws(io);
  ws.next_layer().connect(tcp::endpoint(asio::ip::make_address_v4(kPageHost), kPagePort));
  ws.handshake(std::string(kPageHost) + ":" + std::to_string(kPagePort), "/ws");
  for (int frames = 0; frames < 16; ++frames) {
    beast::flat_buffer buffer;
    ws.read(buffer);
    auto frame = nlohmann::json::parse(beast::buffers_to_string(buffer.data()), nullptr, false);
    if (frame.is_object() && frame.value("type", "") == "welcome") return frame;
  }
  return std::nullopt;
}

TEST(ConsolePlugins, APluginKindsViewsReachThePage) {
  const fs::path folder = fresh_folder("jaus-console-plugin");
  // Its own state folder: the console keeps and locks its operator ID there.
  jaus::test::ChildProcess console({JAUS_CONSOLE_PATH, "--plugin", TEST_ODOMETER_PLUGIN, "--listen",
                                    std::string(kPageHost) + ":" + std::to_string(kPagePort), "--to", "127.0.0.1:9",
                                    "--as", "254.231.40.1"},
                                   (folder / "console.log").string(), jaus::test::ChildProcess::Stdin::inherit,
                                   {"XDG_STATE_HOME=" + (folder / "state").string()});
  ASSERT_TRUE(console.output_shows("page at http://", std::chrono::seconds(20))) << console.output();
  EXPECT_TRUE(console.output_contains("plugin 'test_odometer' (")) << console.output();
  EXPECT_TRUE(console.output_contains("): component kinds plugin_odometer")) << console.output();

  const auto welcome = welcome_from_page();
  ASSERT_TRUE(welcome) << console.output();
  const auto& views = (*welcome)["views"];
  // The plugin kind's ID (150), beside the built-in kinds' (the primitive driver's 33).
  ASSERT_TRUE(views.contains("150")) << welcome->dump();
  EXPECT_EQ(views["150"], nlohmann::json::array({"velocity"}));
  EXPECT_TRUE(views.contains("33")) << welcome->dump();

  console.signal(SIGTERM);
  EXPECT_EQ(console.wait(std::chrono::seconds(10)), 0) << console.output();
  fs::remove_all(folder);
}

TEST(ConsolePlugins, APluginThatDoesNotLoadIsBadUsage) {
  const fs::path folder = fresh_folder("jaus-console-no-plugin");
  jaus::test::ChildProcess console({JAUS_CONSOLE_PATH, "--plugin", (folder / "libnone.so").string(), "--as",
                                    "254.232.40.1"},
                                   (folder / "console.log").string(), jaus::test::ChildProcess::Stdin::inherit,
                                   {"XDG_STATE_HOME=" + (folder / "state").string()});
  EXPECT_EQ(console.wait(std::chrono::seconds(20)), 2) << console.output();
  EXPECT_TRUE(console.output_contains("jaus-console: --plugin: ")) << console.output();
  EXPECT_TRUE(console.output_contains("libnone.so")) << console.output();
  EXPECT_FALSE(console.output_contains("page at")) << "nothing starts";
  fs::remove_all(folder);
}

}  // namespace
