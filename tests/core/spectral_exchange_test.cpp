// A result set in one stage's spectral phase from scalar parameters and read by a later stage's spectral phase
// (Context::set_in_spectral_phase, read_in_spectral_phase): the named parameters become spectral in that chain
// only. Hand-built stages, so that the rule is checked apart from any plugin: a producer publishes p = a + b and
// names only `a`; a reader copies p in its spectral phase (or, in the control chain, reads it in its scalar phase
// after a look-up in prepare, as giqe does with the view zenith).
#include "radchain/chain.hpp"

#include <gtest/gtest.h>

#include <memory>
#include <stdexcept>
#include <string>

namespace {
using namespace radchain;

const Schema& producer_schema() {
  static const Schema s = {number("a", "1"), number("b", "2")};
  return s;
}
const Schema& reader_schema() {
  static const Schema s = {number("c", "3").affects_spectrum()};
  return s;
}

class Producer final : public Stage {
 public:
  Producer(const Params& p, bool exchange) : a_(p.handle("a")), b_(p.handle("b")), exchange_(exchange) {}
  void prepare(Context& c) override {
    ++prepares;
    id_ = c.declare("p", "1", "a + b");
    if (exchange_) c.set_in_spectral_phase(id_, *a_ + *b_, {a_});  // (b deliberately not named)
    else c.results.set(id_, *a_ + *b_);
  }
  void evaluate(Context& c) override { c.results.set(id_, *a_ + *b_); }
  int prepares = 0;

 private:
  const double *a_, *b_;
  bool exchange_;
  ResultId id_{};
};

class Reader final : public Stage {
 public:
  explicit Reader(bool in_spectral_phase) : in_spectral_phase_(in_spectral_phase) {}
  void prepare(Context& c) override {
    source_ = *c.results.find("producer.p");
    if (in_spectral_phase_) copy_ = c.read_in_spectral_phase(source_);
    id_ = c.declare("copy", "1", "p as the spectral phase read it");
  }
  void evaluate(Context& c) override { c.results.set(id_, in_spectral_phase_ ? copy_ : c.results.value(source_)); }

 private:
  bool in_spectral_phase_;
  double copy_ = 0;
  ResultId source_{}, id_{};
};

struct Built {
  Chain chain;
  Producer* producer = nullptr;
};

Built build(bool producer_exchanges, bool reader_in_spectral_phase) {
  Built built;
  StageSlot first;
  first.section = first.plugin = "producer";
  first.params = std::make_unique<Params>("producer", "producer", &producer_schema());
  for (auto& e : first.params->entries()) e.present = true;
  first.params->entry("a").number = 1, first.params->entry("b").number = 2;
  auto producer = std::make_unique<Producer>(*first.params, producer_exchanges);
  built.producer = producer.get();
  first.stage = std::move(producer);
  StageSlot second;
  second.section = second.plugin = "reader";
  second.params = std::make_unique<Params>("reader", "reader", &reader_schema());
  for (auto& e : second.params->entries()) e.present = true;
  second.stage = std::make_unique<Reader>(reader_in_spectral_phase);
  built.chain.stages.push_back(std::move(first));
  built.chain.stages.push_back(std::move(second));
  built.chain.evaluate();
  return built;
}

TEST(SpectralExchange, ANamedParameterIsSpectralWhereALaterSpectralPhaseReadsIt) {
  Built b = build(true, true);
  Chain& chain = b.chain;
  EXPECT_EQ(chain.result("reader.copy"), 3.0);
  const ParameterRef a = chain.parameter("producer.a"), unnamed = chain.parameter("producer.b");
  EXPECT_TRUE(a.spectral());
  EXPECT_FALSE(unnamed.spectral());
  EXPECT_TRUE(chain.parameter("reader.c").spectral());  // its schema's affects_spectrum
  EXPECT_THROW(chain.set_lanes(a, constant_lanes(5.0)), std::logic_error);
  chain.set(a, 10);
  chain.evaluate();
  EXPECT_EQ(b.producer->prepares, 2);
  EXPECT_EQ(chain.result("reader.copy"), 12.0);  // the spectral phase re-ran from the producer
  chain.set(unnamed, 20);
  chain.evaluate();
  EXPECT_EQ(b.producer->prepares, 2);            // not named: scalar (the copy is stale, as the producer declared)
  EXPECT_EQ(chain.result("producer.p"), 30.0);
  EXPECT_EQ(chain.result("reader.copy"), 12.0);
  // run() clears the values; a spectral phase that starts at the reader (its own spectral key) still reads what
  // the producer's spectral phase set.
  chain.set(a, 4);
  chain.evaluate();
  EXPECT_EQ(b.producer->prepares, 3);
  chain.set(chain.parameter("reader.c"), 1);
  EXPECT_EQ(chain.run().value("reader.copy").value(), 24.0);
  EXPECT_EQ(b.producer->prepares, 3);
  chain.invalidate_spectra();
  EXPECT_EQ(chain.run().value("reader.copy").value(), 24.0);
  EXPECT_EQ(b.producer->prepares, 4);
}

TEST(SpectralExchange, ALookUpReadInTheScalarPhaseKeepsTheParameterScalar) {
  Built b = build(true, false);
  const ParameterRef a = b.chain.parameter("producer.a");
  EXPECT_FALSE(a.spectral());
  b.chain.set(a, 10);
  b.chain.evaluate();
  EXPECT_EQ(b.producer->prepares, 1);
  EXPECT_EQ(b.chain.result("reader.copy"), 12.0);
  EXPECT_NO_THROW(b.chain.set_lanes(a, constant_lanes(5.0)));
}

TEST(SpectralExchange, AReadOfAResultNoSpectralPhaseSetIsALogicError) {
  EXPECT_THROW(build(false, true), std::logic_error);
}

}  // namespace
