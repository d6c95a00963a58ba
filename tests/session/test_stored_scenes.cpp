// The scenes a stored study recorded, reproduced from its seeds: for the
// shipped protocols, participants' planned trial seeds and the content hash
// of each trial's scene as a session generates it (the `trial_seed` and
// `scene_hash` columns of every study database these protocols recorded).
// Pinned as literals, printed by the code as it stood before the random
// generators became one family (study/common/random.h); a failure means a
// stored study's trials no longer reproduce. Never regenerate to make a
// change pass: bump kSceneFormatVersion and say why.
#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "study/design/design.h"
#include "study/session/session.h"

namespace dtlab::session {
namespace {

struct Stored {
  int position;  // 1-based, as `dtlab plan` lists it
  std::uint64_t seed;
  const char* scene_hash;
};

struct Case {
  const char* protocol;
  int index;  // enrollment index K, on order row 0
  std::vector<Stored> trials;
};

const std::vector<Case> kCases = {
    {"elmqvist2008.toml", 0,
        {
         {1, 13947942700548049222ULL, "e06165678f9b0bf94b80f3b6c0eb43119474c8a25bcf74832049b0c1db62aa4d"},
         {2, 17448277917406311785ULL, "a1d00e122a5b7bf21f553df0e4fc60ffc3843bb00c5cd7ee1852e22b1220be3a"},
         {3, 5245698813169723530ULL, "74772be72f6a35ef45560c1f0613ed85af231b625c76c6ae18d77b79b165da32"},
         {4, 1213085486837015282ULL, "359d9f41a09c759c317f10f51428e913f6d76e729613ee878455b7af404ee5f4"},
         {5, 14219906441633644054ULL, "1ccb85147d752bb08a4912c708703006393379fcd0e89655db54eebc4659ada5"},
         {6, 4857984398409157512ULL, "2c2bbbfe6467a0cdcdd709a263ba067fe95e880bfe314c967cfae54adb4cb743"},
         {7, 1501397276284369675ULL, "fa4fc7c4dfc7f7d97f97adcd18ff726a52d21523bfc9a34e5c88ae6071195270"},
         {8, 11858957541555725124ULL, "e48d1d2bc41415819a7cda219b635c24c8c812baecc01b1f08c0c4a13a0b34c7"},
         {9, 7921322218267026519ULL, "a25c30e690d12ac8551e8add4cb37c223e20fbd31bf819a14933a54b4e1bc684"},
         {10, 3146669106602388104ULL, "c6211fb6c8fd11bc0a87e43b3e12578d0cd8e0faf9c30b17b5258f6352296af9"},
         {11, 13981798767501165029ULL, "f6ba19b4b10cd4956094af944b88193f2a1508f21acddcc85457b9472cd51181"},
         {12, 7285274668948140294ULL, "99d590ae2563e85e61e9f415bcaa00687a79100aebbd92c8482f722314d78cdb"},
         {13, 12059966761350003694ULL, "bd2cbbd131f306ad5ee838da4944d563e74d5969b4325cb049ab59c8b30c00f3"},
         {14, 14037998998845826546ULL, "f91738ef349036962d068e72362726951433ab63ed38729ce516324f59dd2a5c"},
         {15, 3872732134827883216ULL, "8479dd6b7afd0bf1b919e923c9e8abc63f9bd6d0ee297fe20e8a1720d4ea20db"},
         {16, 17223604739144122895ULL, "06c8cdb48db882b3b827838db91340bfb611fa4466df282ef59a9bdf5278036f"},
         {17, 9397107870924203922ULL, "cadb59602dccfedc4d6ef69a1fe17afa93b906b1b016cdfcbe66a583b63cebc1"},
         {18, 8767740824949740896ULL, "c893f7a086d8e52ed2d1640729f7ffe4f15ab067efd58d087429b41ab4af81f9"},
         {19, 13301302787798597361ULL, "ad701e6456b1370fe10dacc276ac84f5c4dacb85796835b4e1eb5aec60bb1add"},
         {20, 5858837979812757405ULL, "247ce16be74668b48c174d6a1abd86a3fcb0fb6aa701a027f8c83080ed4bbd42"},
         {21, 17649167308018766436ULL, "77aec9e5ba9910a0dc5e7d45d5a6317f628bfff32a6c6cf8cc3e73f177ba9072"},
         {22, 12435045066016316271ULL, "6073f4a606142e6be2a194cc0a4301a763297af97aeb5c95fede4f51f667bf2f"},
         {23, 18162013094861317960ULL, "baca5cc18e5479a445401b94175f53405cafdd5d515f26387307024c19894375"},
         {24, 16161111821191113536ULL, "d7fbdb19b2415518da9e1786940c7ec51279814df52cd8cd28924f6541d09a9f"},
        }},
    {"elmqvist2008.toml", 5,
        {
         {1, 5759492632512947314ULL, "593cdac045e7b71a4926e8d2d16b5e52b48b90ca4b30f8d197a6f9369c2f913f"},
         {2, 10001124129900552423ULL, "f09751d430c0d9ffd3acd6a120d3b91094e8756d7ccae936d1aae6810f647e28"},
         {3, 13404968352147687346ULL, "cd9a17ef947d27b1923add6ce95f3a9485adbe65ae1e6ce64ca98a4925df3752"},
         {4, 17561121880357102090ULL, "a4cbfd875876d802ba0790a1fd5a194fae5c855d6189fc34b95215cf104259ad"},
         {5, 11237012833226892313ULL, "524b4008092bc1a7074995e5a53776245ac8d2a3f57f76dac5b563c821d324fb"},
         {6, 7075328144327453625ULL, "3371bd903878da407492aba50790bb9cfdfc024be3635b54e82312ce349bce63"},
         {7, 15813380360059712361ULL, "fe1edf8410e8d9a267faa589fcbea325af1c70206db96bb482231d58af2cb420"},
         {8, 10065637895900219693ULL, "5bd3f82ee6b77896eed803a89b269dec777f3809a265028595f4fa56e03809cf"},
         {9, 5880867893447171446ULL, "6f545c688ee7e3704b77c43475b7a6371d5bb3a4c9e49b0f8ae20564bf89c6f9"},
         {10, 520602615732249388ULL, "34a1d2b4350403eb7ed3b20776ff8fe5c9dda6b8c5bbdbd68b3a5f8b764a069d"},
         {11, 6335355123647899005ULL, "15dc7cad07f14b90300e9f6867119e04727917fdb4a1d18c082281ea0a1eea77"},
         {12, 5661060106760343091ULL, "a0d282cf13206329415b6e33deea1a50e168b95f37f4282036835ff6c681a455"},
         {13, 11554443191577835786ULL, "352ad76ad7f57af14119a3f56b4eaf5c536576ee5cf3dba9808bc19aaf79176c"},
         {14, 6658667963058501293ULL, "c357f358262a9fbf0d1358049eb5293671d9a70f75e53f382945dc34cc3ee7e9"},
         {15, 11869647594532182455ULL, "a77242a0488efb08276d77bb3fc7cb608c32525c51ff3af46c1fdcb2786c77e5"},
         {16, 10826943894640463461ULL, "2ef5480481fc0a64458fc9e4c455cb6e8a7bea7c0c9ff303150c5506a13b066b"},
         {17, 806653774529227305ULL, "1eef5be50af576eb5a1e77c4a4466c0d363b754b08c9ed509a02725998192233"},
         {18, 4208690949061415507ULL, "d0cfb352de9b9c732d6925399244e2ffe50693b0302c14ed5371a69da18222f1"},
         {19, 8495205141031844997ULL, "73b0182c46be08b41076a2b10154095715c6de39ca499daf65c46e59524dae3a"},
         {20, 17133338719061468801ULL, "fe3e88dd53efca048f01df400af293a2177ea72fc35b7bd2db1b2f9688d1df90"},
         {21, 8865394948186698020ULL, "9d98b66bd30d9bef669f3621d40383c74978fc5c04d54c92732cfb26ed1e5db3"},
         {22, 17032370544948960372ULL, "1b5d3f450190900132e4dc291d8b816bacd2d9868d3b339d4ef66f937caf9288"},
         {23, 11506116803154167686ULL, "1edc82ab07391fcf0edbd7fa3157ad7444c3307d53e981c8655885e443ef2a98"},
         {24, 4818561873646766355ULL, "fcb5ca01e996f7f12b28451968176388e6be0f463fea8c572ca1130f192999b0"},
        }},
};

TEST(StoredScenes, SeedsAndSceneHashesReproduce) {
  for (const Case& c : kCases) {
    auto p = protocol::load_protocol(std::string(DTLAB_SOURCE_DIR) + "/protocols/" + c.protocol);
    ASSERT_TRUE(p.ok()) << p.error().to_string();
    const design::Plan plan = design::make_plan(*p, c.index, 0);
    ASSERT_EQ(plan.trials.size(), c.trials.size()) << c.protocol;
    for (std::size_t i = 0; i < plan.trials.size(); ++i) {
      const design::PlannedTrial& t = plan.trials[i];
      const Stored& want = c.trials[i];
      SCOPED_TRACE(std::string(c.protocol) + " K=" + std::to_string(c.index) + " position " + std::to_string(want.position));
      EXPECT_EQ(t.seed, want.seed);
      auto setup = trial_setup(*p, t);
      ASSERT_TRUE(setup.ok());
      auto sc = trial_scene(setup.value(), t);
      ASSERT_TRUE(sc.ok());
      EXPECT_EQ(sc->hash, want.scene_hash);
    }
  }
}

}  // namespace
}  // namespace dtlab::session
