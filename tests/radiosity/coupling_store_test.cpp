// The solver's coupling store: slots keep their values and addresses while it grows.
#include <gtest/gtest.h>

#include "radiosity/coupling_store.h"

namespace radquad {
namespace {

TEST(CouplingStore, SlotsKeepTheirValuesAndAddressesAsTheStoreGrows) {
  for (int functions : {1, 9, 16}) {
    CouplingStore store(functions);
    store.resize(3);
    EXPECT_EQ(store.size(), 3u);
    EXPECT_TRUE(store[2].isZero(0.0));
    store[1].setConstant(1.5);
    const double* first = store.data(1);
    // Past three blocks of 2 MiB (radiosity/coupling_store.cpp), so that blocks are added.
    const std::size_t slotBytes = sizeof(double) * std::size_t(functions * functions);
    const std::size_t links = 3 * ((std::size_t(2) << 20) / slotBytes) + 5;
    store.resize(links);
    EXPECT_EQ(store.size(), links);
    for (std::size_t k = 0; k < links; k += 97) store[k](0, functions - 1) = double(k);
    EXPECT_EQ(store.data(1), first);
    EXPECT_EQ(store[1](functions - 1, 0), 1.5);
    for (std::size_t k = 97; k < links; k += 97) {
      EXPECT_EQ(store[k](0, functions - 1), double(k)) << k;
      EXPECT_EQ(store[k].rows(), functions);
      EXPECT_EQ(store[k].cols(), functions);
    }
    store.resize(10);  // never shrinks
    EXPECT_EQ(store.size(), links);
  }
}

}  // namespace
}  // namespace radquad
