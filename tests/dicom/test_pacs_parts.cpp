// The parts of arbor_pacs that need no archive: WADO-RS multipart parsing
// (against bodies built here, cut at every possible place), node and
// pacs:// parsing, the node file.  The archive itself is tested against a
// real Orthanc in integration/test_pacs.py.
#include "dicom/multipart_stream.hpp"
#include "dicom/pacs_input.hpp"
#include "dicom/pacs_node.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <random>

namespace arbor::dicom {
namespace {

std::string body_of(const std::vector<std::string> &parts, const std::string &boundary)
{
    std::string b = "preamble to ignore\r\n";
    for (const std::string &p : parts)
        b += "--" + boundary + "\r\nContent-Type: application/dicom\r\n\r\n" + p + "\r\n";
    return b + "--" + boundary + "--\r\nepilogue";
}

std::vector<std::string> parse_in_pieces(const std::string &body, const std::string &boundary,
                                         const std::vector<std::size_t> &cuts, bool *finished)
{
    std::vector<std::string> got;
    MultipartStream s(boundary, [&](const std::string &headers, std::string &part) {
        EXPECT_EQ(headers, "Content-Type: application/dicom");
        got.push_back(part);
    });
    std::size_t at = 0;
    for (std::size_t cut : cuts) {
        s.feed(body.data() + at, cut - at);
        at = cut;
    }
    s.feed(body.data() + at, body.size() - at);
    *finished = s.finished();
    return got;
}

TEST(MultipartStream, EveryCutGivesTheSameParts)
{
    const std::string boundary = "b0undary-42";
    // Parts that hold CRLFs, dashes and a near-delimiter.
    const std::vector<std::string> parts = {"DICM\r\n--b0undary-4", std::string(3000, '\0'), "", "\r\n--x\r\n"};
    const std::string body = body_of(parts, boundary);
    for (std::size_t cut = 0; cut <= body.size(); ++cut) {
        bool finished = false;
        EXPECT_EQ(parse_in_pieces(body, boundary, {cut}, &finished), parts) << "cut at " << cut;
        EXPECT_TRUE(finished);
    }
    std::mt19937 random(7);
    for (int trial = 0; trial < 200; ++trial) {
        std::vector<std::size_t> cuts;
        std::size_t at = 0;
        while ((at += random() % 40) < body.size())
            cuts.push_back(at);
        bool finished = false;
        EXPECT_EQ(parse_in_pieces(body, boundary, cuts, &finished), parts);
        EXPECT_TRUE(finished);
    }
}

TEST(MultipartStream, ATruncatedBodyIsNotFinished)
{
    const std::string body = body_of({"one", "two"}, "B");
    bool finished = true;
    const auto got = parse_in_pieces(body.substr(0, body.find("two") + 2), "B", {}, &finished);
    EXPECT_EQ(got, std::vector<std::string>{"one"});
    EXPECT_FALSE(finished);
}

TEST(MultipartStream, BoundaryFromTheContentType)
{
    EXPECT_EQ(multipart_boundary("multipart/related; type=\"application/dicom\"; boundary=abc-1"), "abc-1");
    EXPECT_EQ(multipart_boundary(" multipart/related; Boundary=\"q u;o\"; type=x\r\n"), "q u;o");
    EXPECT_EQ(multipart_boundary("application/dicom+json"), "");
}

TEST(PacsNode, InlineForms)
{
    const PacsNode n = parse_inline_node("ORTHANC@pacs.example:4242");
    EXPECT_EQ(n.kind, PacsNode::Kind::Dimse);
    EXPECT_EQ(n.aet, "ORTHANC");
    EXPECT_EQ(n.host, "pacs.example");
    EXPECT_EQ(n.port, 4242);
    EXPECT_EQ(n.describe(), "ORTHANC@pacs.example:4242");
    EXPECT_EQ(n.cache_key(), "ORTHANC@pacs.example_4242");
    const PacsNode w = parse_inline_node("https://pacs.example/dicom-web/");
    EXPECT_EQ(w.kind, PacsNode::Kind::DicomWeb);
    EXPECT_EQ(w.url, "https://pacs.example/dicom-web");
    for (const char *bad : {"ORTHANC@host", "@host:1", "ORTHANC@:1", "A@h:0", "A@h:70000", "A@h:12x",
                            "AN_AE_TITLE_LONGER_THAN_16@h:1", "https://user:secret@pacs.example/dicom-web", "plain"})
        EXPECT_THROW(parse_inline_node(bad), std::invalid_argument) << bad;
}

TEST(PacsNode, FindByNameOrInlineAndSayWhatIsConfigured)
{
    std::vector<PacsNode> nodes(1);
    nodes[0].name = "archive";
    nodes[0].aet = "A";
    nodes[0].host = "h";
    nodes[0].port = 104;
    EXPECT_EQ(find_node("archive", nodes).describe(), "A@h:104");
    EXPECT_EQ(find_node("B@h:11112", nodes).port, 11112);
    try {
        find_node("other", nodes);
        FAIL();
    } catch (const std::invalid_argument &e) {
        EXPECT_NE(std::string(e.what()).find("configured: archive"), std::string::npos);
    }
}

TEST(PacsNode, FileRoundTripKeepsVariablesNotTheirValues)
{
    const auto file = std::filesystem::path(testing::TempDir()) / "arbor-nodes-test" / "pacs-nodes.json";
    std::filesystem::remove_all(file.parent_path());
    ::setenv("ARBOR_TEST_PACS_SECRET", "s3cr3t", 1);
    PacsNode d;
    d.name = "dimse";
    d.aet = "ORTHANC";
    d.host = "localhost";
    d.port = 4242;
    d.our_port = 11112;
    PacsNode w;
    w.name = "web";
    w.kind = PacsNode::Kind::DicomWeb;
    w.url = "http://localhost:8042/dicom-web";
    w.secret.user = "u";
    w.secret.password_env = "ARBOR_TEST_PACS_SECRET";
    write_nodes(file, {d, w});
    std::ifstream in(file);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_EQ(text.find("s3cr3t"), std::string::npos);
    const auto back = read_nodes(file);
    ASSERT_EQ(back.size(), 2u);
    EXPECT_EQ(back[0].describe(), "ORTHANC@localhost:4242");
    EXPECT_EQ(back[0].our_port, 11112);
    EXPECT_EQ(back[1].secret.password, "s3cr3t");
    EXPECT_EQ(back[1].authentication(), "basic (user u)");
    ::unsetenv("ARBOR_TEST_PACS_SECRET");
    EXPECT_THROW(read_nodes(file), std::runtime_error); // the variable it names is gone
    std::ofstream(file) << R"({"format": "arbor-pacs-nodes/1", "nodes": [{"name": "x", "kind": "dimse"}]})";
    EXPECT_THROW(read_nodes(file), std::runtime_error);
    std::ofstream(file) << "not json";
    EXPECT_THROW(read_nodes(file), std::runtime_error);
    EXPECT_TRUE(read_nodes(file.parent_path() / "absent.json").empty());
}

TEST(PacsUri, Forms)
{
    EXPECT_TRUE(is_pacs_uri("pacs://archive/1.2.3"));
    EXPECT_FALSE(is_pacs_uri("/data/pacs://x"));
    PacsUri u = parse_pacs_uri("pacs://ORTHANC@h:4242/1.2.840.1");
    EXPECT_EQ(u.node, "ORTHANC@h:4242");
    EXPECT_EQ(u.series_uid, "1.2.840.1");
    u = parse_pacs_uri("pacs://http://h:8042/dicom-web/1.2.3");
    EXPECT_EQ(u.node, "http://h:8042/dicom-web");
    EXPECT_EQ(u.series_uid, "1.2.3");
    for (const char *bad : {"pacs://", "pacs://archive", "pacs://archive/", "pacs:///1.2", "pacs://a/1.2.x"})
        EXPECT_THROW(parse_pacs_uri(bad), std::invalid_argument) << bad;
}

} // namespace
} // namespace arbor::dicom
