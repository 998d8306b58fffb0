// sim/schema: the table-driven reader on a table written by hand (every kind of node):
// values stored where the table says, defaults, nested objects, arrays, and errors that name
// the key and the value.
#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>

extern "C" {
#include "sim/schema.h"
}

namespace
{

struct Item {
    double v;
};
struct Rec {
    double angle;
    uint32_t count;
    uint64_t big;
    bool flag;
    char name[8];
    int kind;
    double inner;
    Item items[4];
    size_t n_items;
};

const char *const kKinds[] = {"a", "bb"};
const sim_schema_node_t kItem[] = {{"v", SIM_SCHEMA_NUMBER, true, false, false, 0, 0, 10, 1.0,
                                    offsetof(Item, v), sizeof(double), 0, 0, NULL, 0, NULL, 0}};
const sim_schema_node_t kItemObj[] = {
    {"", SIM_SCHEMA_OBJECT, true, false, true, 0, 0, 0, 1, 0, 0, 0, 0, kItem, 1, NULL, 0}};
const sim_schema_node_t kInner[] = {{"x", SIM_SCHEMA_NUMBER, false, true, false, 2.5, 0, 10, 1.0,
                                     offsetof(Rec, inner), sizeof(double), 0, 0, NULL, 0, NULL, 0}};
const sim_schema_node_t kMembers[] = {
    {"angle_deg", SIM_SCHEMA_NUMBER, true, false, false, 0, -360, 360, M_PI / 180,
     offsetof(Rec, angle), sizeof(double), 0, 0, NULL, 0, NULL, 0},
    {"count", SIM_SCHEMA_INTEGER, false, true, false, 5, 1, 100, 1, offsetof(Rec, count),
     sizeof(uint32_t), 0, 0, NULL, 0, NULL, 0},
    {"big", SIM_SCHEMA_INTEGER, false, false, false, 0, 0, 9007199254740991.0, 1,
     offsetof(Rec, big), sizeof(uint64_t), 0, 0, NULL, 0, NULL, 0},
    {"flag", SIM_SCHEMA_BOOLEAN, false, true, false, 1, 0, 0, 1, offsetof(Rec, flag), sizeof(bool),
     0, 0, NULL, 0, NULL, 0},
    {"name", SIM_SCHEMA_STRING, false, false, false, 0, 0, 7, 1, offsetof(Rec, name), 8, 0, 0, NULL,
     0, NULL, 0},
    {"kind", SIM_SCHEMA_ENUM, false, true, false, 1, 0, 0, 1, offsetof(Rec, kind), sizeof(int), 0,
     0, NULL, 0, kKinds, 2},
    {"inner", SIM_SCHEMA_OBJECT, false, false, true, 0, 0, 0, 1, 0, 0, 0, 0, kInner, 1, NULL, 0},
    {"items", SIM_SCHEMA_ARRAY, false, false, false, 0, 1, 4, 1, offsetof(Rec, items), 0,
     offsetof(Rec, n_items), sizeof(Item), kItemObj, 1, NULL, 0},
};
const sim_schema_node_t kRoot = {"", SIM_SCHEMA_OBJECT, true, false, true, 0, 0, 0, 1, 0, 0, 0,
                                 0,  kMembers,          8,    NULL,  0};

int read(const char *text, Rec *r, std::string *err)
{
    json_error_t je;
    json_t *v = json_loads(text, 0, &je);
    EXPECT_NE(v, nullptr) << text;
    *r = Rec{};
    char e[256] = "";
    int rc = sim_schema_read(&kRoot, v, r, "", "test", e, sizeof e);
    json_decref(v);
    *err = e;
    return rc;
}

TEST(Schema, StoresEveryKindWhereTheTableSays)
{
    Rec r;
    std::string err;
    ASSERT_EQ(read(R"({"angle_deg": 90, "count": 7, "big": 9007199254740991, "flag": false,
                      "name": "abc", "kind": "a", "inner": {"x": 4}, "items": [{"v": 1}, {"v": 2}]})",
                   &r, &err),
              0)
        << err;
    EXPECT_DOUBLE_EQ(r.angle, M_PI / 2);
    EXPECT_EQ(r.count, 7u);
    EXPECT_EQ(r.big, 9007199254740991ull);
    EXPECT_FALSE(r.flag);
    EXPECT_STREQ(r.name, "abc");
    EXPECT_EQ(r.kind, 0);
    EXPECT_EQ(r.inner, 4.0);
    ASSERT_EQ(r.n_items, 2u);
    EXPECT_EQ(r.items[1].v, 2.0);
}

TEST(Schema, AbsentKeysTakeTheirDefaultsEvenInAbsentObjects)
{
    Rec r;
    std::string err;
    ASSERT_EQ(read(R"({"angle_deg": -30})", &r, &err), 0) << err;
    EXPECT_EQ(r.count, 5u);
    EXPECT_TRUE(r.flag);
    EXPECT_EQ(r.kind, 1);
    EXPECT_EQ(r.inner, 2.5); // "inner" absent: its member's default
    EXPECT_EQ(r.n_items, 0u);
}

TEST(Schema, ErrorsNameTheKeyAndTheValue)
{
    const char *cases[][2] = {
        {R"({})", "missing \"angle_deg\""},
        {R"({"angle_deg": 400})", "angle_deg: 400 is out of range [-360, 360]"},
        {R"({"angle_deg": "x"})", "angle_deg: expected a number, got \"x\""},
        {R"({"angle_deg": 0, "count": 2.5})", "count: 2.5 is not an integer"},
        {R"({"angle_deg": 0, "flag": 1})", "flag: expected true or false, got 1"},
        {R"({"angle_deg": 0, "name": "toolongname"})", "name: \"toolongname...\" is longer than 7"},
        {R"({"angle_deg": 0, "kind": "c"})", "kind: \"c\" is not one of \"a\", \"bb\""},
        {R"({"angle_deg": 0, "inner": 3})", "inner: expected an object"},
        {R"({"angle_deg": 0, "inner": {"x": 11}})", "inner.x: 11 is out of range"},
        {R"({"angle_deg": 0, "items": []})", "items: 0 entries, expected 1 to 4"},
        {R"({"angle_deg": 0, "items": [{"v": 1}, 3]})", "items[1]: expected an object"},
        {R"({"angle_deg": 0, "items": [{"w": 1}]})", "missing \"items[0].v\""},
    };
    for (auto &c : cases) {
        Rec r;
        std::string err;
        EXPECT_EQ(read(c[0], &r, &err), -1) << c[0];
        EXPECT_NE(err.find(c[1]), std::string::npos) << "got: " << err << " / want: " << c[1];
    }
}

} // namespace
