// The DevTools client itself, on a page of its own (no console): Chromium
// starts headless, a tab loads, the page reads keys and clicks as a user's,
// a screenshot is a PNG, and closing the tab fires the page's pagehide.
#include <gtest/gtest.h>

#include <fstream>

#include "cdp_client.hpp"
#include "require_chromium.hpp"

namespace jaus::test::browser {
namespace {

// A page that counts what it receives, reachable without a server.
constexpr const char* kPage =
    "data:text/html,<button id=b onclick='window.clicks=(window.clicks||0)+1' style='width:200px;height:80px'>b</button>"
    "<script>window.keys=[];addEventListener('keydown',e=>keys.push('down '+e.code));"
    "addEventListener('keyup',e=>keys.push('up '+e.code));</script>";

TEST(CdpClient, LoadsAPageTypesClicksAndTakesAScreenshot) {
  JAUS_REQUIRE_CHROMIUM();
  auto chromium = Chromium::launch(800, 600);
  ASSERT_TRUE(chromium) << chromium.error().message();
  auto cdp = CdpClient::connect(**chromium);
  ASSERT_TRUE(cdp) << cdp.error().message();
  auto tab = Tab::open(**cdp, kPage);
  ASSERT_TRUE(tab) << tab.error().message() << (*chromium)->log();

  auto sum = tab->evaluate("1 + 2");
  ASSERT_TRUE(sum) << sum.error().message();
  EXPECT_EQ(*sum, 3);
  EXPECT_FALSE(tab->evaluate("nothing.here"));  // the page's exception is an error, not a value

  ASSERT_TRUE(tab->key_down("ArrowUp"));
  ASSERT_TRUE(tab->key_up("ArrowUp"));
  ASSERT_TRUE(tab->key_down("KeyW"));
  auto keys = tab->evaluate("keys");
  ASSERT_TRUE(keys);
  EXPECT_EQ(*keys, (Json{"down ArrowUp", "up ArrowUp", "down KeyW"}));

  ASSERT_TRUE(tab->click("#b"));
  auto clicked = tab->wait_until("window.clicks === 1", 5s);
  ASSERT_TRUE(clicked);
  EXPECT_EQ(*clicked, true);
  EXPECT_FALSE(tab->click("#nothing"));

  const auto file = std::filesystem::temp_directory_path() / ("cdp-client-test-" + std::to_string(::getpid()) + ".png");
  ASSERT_TRUE(tab->screenshot(file));
  std::ifstream png(file, std::ios::binary);
  std::string signature(8, '\0');
  png.read(signature.data(), 8);
  EXPECT_EQ(signature, std::string("\x89PNG\r\n\x1a\n", 8));
  std::filesystem::remove(file);

  ASSERT_TRUE(tab->close());
  auto targets = (*cdp)->call("Target.getTargets");
  ASSERT_TRUE(targets);
  for (const auto& target : (*targets)["targetInfos"]) EXPECT_NE(target["targetId"], tab->target_id());
}

TEST(CdpClient, RemovesItsProfileDirectoryAndStopsChromium) {
  JAUS_REQUIRE_CHROMIUM();
  std::filesystem::path profile;
  {
    auto chromium = Chromium::launch(400, 300);
    ASSERT_TRUE(chromium) << chromium.error().message();
    auto cdp = CdpClient::connect(**chromium);
    ASSERT_TRUE(cdp);
    auto version = (*cdp)->call("Browser.getVersion");
    ASSERT_TRUE(version) << version.error().message();
    EXPECT_NE((*version)["product"].get<std::string>().find("Chrome"), std::string::npos);
    profile = (*chromium)->directory();
    EXPECT_TRUE(std::filesystem::exists(profile / "profile" / "DevToolsActivePort"));
  }
  ASSERT_FALSE(profile.empty());
  EXPECT_FALSE(std::filesystem::exists(profile));
}

}  // namespace
}  // namespace jaus::test::browser
