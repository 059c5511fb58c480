// The list manager's element store (list_manager_elements.hpp): the rules of
// the JSS List Manager service (docs/jss.md, "List Manager and Local Waypoint
// List Driver") and the Reject Element Request code of each broken one;
// a rejected request leaves the list as it was.
#include <gtest/gtest.h>

#include <vector>

#include "list_manager_elements.hpp"

namespace jaus::components_jss {
namespace list_elements_test {

ListElement element(std::uint16_t uid, std::uint16_t previous, std::uint16_t next) {
  return ListElement{uid, previous, next, 0, {0x0d, 0x04}};
}

std::optional<ElementReject> set(ListElements& list, std::vector<ListElement> elements) {
  auto r = list.set(elements);
  if (r) return std::nullopt;
  return r.error().code;
}

using Uids = std::vector<std::uint16_t>;

TEST(JssListElements, AppendedOneByOneOrAllAtOnce) {
  ListElements one_by_one(100);
  EXPECT_FALSE(set(one_by_one, {element(1, 0, 0)}));
  EXPECT_FALSE(set(one_by_one, {element(2, 1, 0)}));
  EXPECT_FALSE(set(one_by_one, {element(3, 2, 0)}));
  EXPECT_FALSE(set(one_by_one, {element(4, 3, 0)}));
  EXPECT_EQ(one_by_one.in_order(), (Uids{1, 2, 3, 4}));
  EXPECT_EQ(one_by_one.find(1)->next_uid, 2);  // the neighbour's link followed
  EXPECT_EQ(one_by_one.find(4)->next_uid, 0);

  ListElements at_once(100);
  EXPECT_FALSE(set(at_once, {element(10, 0, 20), element(20, 10, 30), element(30, 20, 0)}));
  EXPECT_EQ(at_once.in_order(), (Uids{10, 20, 30}));
  EXPECT_EQ(at_once.size(), 3u);
}

TEST(JssListElements, InsertBetweenAndBeforeTheHead) {
  ListElements list(100);
  ASSERT_FALSE(set(list, {element(1, 0, 2), element(2, 1, 0)}));
  EXPECT_FALSE(set(list, {element(5, 1, 2)}));
  EXPECT_EQ(list.in_order(), (Uids{1, 5, 2}));
  EXPECT_FALSE(set(list, {element(9, 0, 1)}));
  EXPECT_EQ(list.in_order(), (Uids{9, 1, 5, 2}));
  EXPECT_EQ(list.find(1)->previous_uid, 9);
}

TEST(JssListElements, EachBrokenRuleHasItsCodeAndChangesNothing) {
  ListElements list(3);
  ASSERT_FALSE(set(list, {element(1, 0, 2), element(2, 1, 0)}));
  const Uids before{1, 2};
  EXPECT_EQ(set(list, {element(0, 2, 0)}), ElementReject::invalid_element_id);
  EXPECT_EQ(set(list, {element(65535, 2, 0)}), ElementReject::invalid_element_id);
  EXPECT_EQ(set(list, {element(3, 7, 0)}), ElementReject::invalid_previous);   // no such previous
  EXPECT_EQ(set(list, {element(3, 2, 8)}), ElementReject::invalid_next);       // no such next
  EXPECT_EQ(set(list, {element(3, 3, 0)}), ElementReject::invalid_previous);   // itself
  EXPECT_EQ(set(list, {element(3, 2, 3)}), ElementReject::invalid_next);       // itself
  EXPECT_EQ(set(list, {element(3, 0, 0)}), ElementReject::invalid_previous);   // a second head
  EXPECT_EQ(set(list, {element(3, 1, 0)}), ElementReject::invalid_previous);   // 2 left behind 1
  // A valid element after an invalid one in the same request: none applied.
  EXPECT_EQ(set(list, {element(3, 2, 0), element(4, 9, 0)}), ElementReject::invalid_previous);
  EXPECT_EQ(list.in_order(), before);
  EXPECT_FALSE(set(list, {element(3, 2, 0)}));
  EXPECT_EQ(set(list, {element(4, 3, 0)}), ElementReject::out_of_memory);
  EXPECT_EQ(list.in_order(), (Uids{1, 2, 3}));
}

TEST(JssListElements, DeleteRelinksAndAllEmpties) {
  ListElements list(100);
  ASSERT_FALSE(set(list, {element(1, 0, 2), element(2, 1, 3), element(3, 2, 0)}));
  const std::vector<std::uint16_t> missing{7};
  EXPECT_EQ(list.remove(missing).error().code, ElementReject::not_found);
  const std::vector<std::uint16_t> middle{2};
  ASSERT_TRUE(list.remove(middle));
  EXPECT_EQ(list.in_order(), (Uids{1, 3}));
  EXPECT_EQ(list.find(3)->previous_uid, 1);
  const std::vector<std::uint16_t> head{1};
  ASSERT_TRUE(list.remove(head));
  EXPECT_EQ(list.find(3)->previous_uid, 0);
  const std::vector<std::uint16_t> all{65535};
  ASSERT_TRUE(list.remove(all));
  EXPECT_TRUE(list.empty());
}

TEST(JssListElements, CircularListRunsOnceRound) {
  ListElements list(100);
  ASSERT_FALSE(set(list, {element(1, 0, 2), element(2, 1, 3), element(3, 2, 1)}));
  EXPECT_EQ(list.find(1)->previous_uid, 0);  // the head stays the head
  EXPECT_EQ(list.in_order(), (Uids{1, 2, 3}));
  std::vector<std::uint16_t> from2;
  for (const ListElement* e : list.from(2)) from2.push_back(e->uid);
  EXPECT_EQ(from2, (Uids{2, 3, 1}));
  const std::vector<std::uint16_t> head{1};
  ASSERT_TRUE(list.remove(head));
  EXPECT_EQ(list.in_order(), (Uids{2, 3}));
  EXPECT_EQ(list.find(3)->next_uid, 2);  // still a circle
  EXPECT_TRUE(list.from(42).empty());
}

TEST(JssListElements, SettingAnExistingUidMovesIt) {
  ListElements list(100);
  ASSERT_FALSE(set(list, {element(1, 0, 2), element(2, 1, 3), element(3, 2, 0)}));
  EXPECT_FALSE(set(list, {element(1, 3, 0)}));  // the head to the end
  EXPECT_EQ(list.in_order(), (Uids{2, 3, 1}));
}

}  // namespace list_elements_test
}  // namespace jaus::components_jss
