// Lab 4, section 10: incremental broad phase - a dynamic AABB tree of fat boxes: the sibling
// chosen by surface-area cost, and the walk up the tree that rotates and refits.
#include <algorithm>

#include "physlab/broadphase.hpp"
#include "physlab/error.hpp"

namespace physlab {

// ---------------------------------------------------------------------------------------------
// Dynamic AABB tree (section 10.1)

int DynamicAabbTree::pickSibling(const Aabb& box) const {
  int index = root_;
  while (!nodes_[static_cast<std::size_t>(index)].isLeaf()) {
    const Node& node = nodes_[static_cast<std::size_t>(index)];
    // Cost of pairing the box with this node, and what every deeper pairing inherits
    const double combined = surfaceArea(enclose(node.box, box));
    const double here = 2.0 * combined;
    const double inherited = 2.0 * (combined - surfaceArea(node.box));
    // Cost of descending into each child: its growth, or its whole new parent for a leaf
    const auto descend = [&](int child) {
      const Node& c = nodes_[static_cast<std::size_t>(child)];
      const double grown = surfaceArea(enclose(c.box, box));
      return inherited + (c.isLeaf() ? grown : grown - surfaceArea(c.box));
    };
    const double cost1 = descend(node.child1);
    const double cost2 = descend(node.child2);
    // Stop here when both children cost more; else go to the cheaper one
    if (here < cost1 && here < cost2) break;
    index = cost1 <= cost2 ? node.child1 : node.child2;
  }
  return index;
}

void DynamicAabbTree::refitUpward(int node) {
  // Walk to the root: balance each node, then refit its box and height from its children
  while (node != kNull) {
    node = balance(node);
    Node& n = nodes_[static_cast<std::size_t>(node)];
    const Node& c1 = nodes_[static_cast<std::size_t>(n.child1)];
    const Node& c2 = nodes_[static_cast<std::size_t>(n.child2)];
    n.box = enclose(c1.box, c2.box);
    n.height = 1 + std::max(c1.height, c2.height);
    node = n.parent;
  }
}

int DynamicAabbTree::balance(int a) {
  Node& A = nodes_[static_cast<std::size_t>(a)];
  if (A.isLeaf()) return a;
  // Find the taller child C, if it is more than one level taller than the other, B
  const int b1 = A.child1, b2 = A.child2;
  const int skew = nodes_[static_cast<std::size_t>(b2)].height - nodes_[static_cast<std::size_t>(b1)].height;
  if (skew >= -1 && skew <= 1) return a;
  const int c = skew > 1 ? b2 : b1;
  Node& C = nodes_[static_cast<std::size_t>(c)];
  // C moves up into a's place: a's parent now points at C, and a becomes C's child
  C.parent = A.parent;
  A.parent = c;
  if (C.parent == kNull) {
    root_ = c;
  } else {
    Node& P = nodes_[static_cast<std::size_t>(C.parent)];
    (P.child1 == a ? P.child1 : P.child2) = c;
  }
  // C keeps its taller child T; a takes the shorter one S where C was
  const int f = C.child1, g = C.child2;
  const bool f_taller = nodes_[static_cast<std::size_t>(f)].height > nodes_[static_cast<std::size_t>(g)].height;
  const int taller = f_taller ? f : g, shorter = f_taller ? g : f;
  C.child1 = a;
  C.child2 = taller;
  (A.child1 == c ? A.child1 : A.child2) = shorter;
  nodes_[static_cast<std::size_t>(shorter)].parent = a;
  // Refit a first (now C's child), then C
  const Node& a1 = nodes_[static_cast<std::size_t>(A.child1)];
  const Node& a2 = nodes_[static_cast<std::size_t>(A.child2)];
  A.box = enclose(a1.box, a2.box);
  A.height = 1 + std::max(a1.height, a2.height);
  const Node& t = nodes_[static_cast<std::size_t>(taller)];
  C.box = enclose(A.box, t.box);
  C.height = 1 + std::max(A.height, t.height);
  return c;
}

}  // namespace physlab
