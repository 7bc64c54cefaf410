// Lab 4, section 10: incremental broad phase - a dynamic AABB tree of fat boxes: the sibling
// chosen by surface-area cost, and the walk up the tree that rotates and refits.
#include <algorithm>

#include "physlab/broadphase.hpp"
#include "physlab/error.hpp"

namespace physlab {

// ---------------------------------------------------------------------------------------------
// Dynamic AABB tree (section 10.1)

int DynamicAabbTree::pickSibling(const Aabb& box) const {
  // Cost of pairing the box with this node, and what every deeper pairing inherits
  // TODO(student): start at root_; while the node is internal: A = surfaceArea(enclose(node.box, box)); here = 2 A; inherited = 2 (A - surfaceArea(node.box)).
  // Cost of descending into each child: its growth, or its whole new parent for a leaf
  // TODO(student): child C: inherited + surfaceArea(enclose(C.box, box)), minus surfaceArea(C.box) if C is internal.
  // Stop here when both children cost more; else go to the cheaper one
  // TODO(student): break if here < both costs (strictly); else go to child1 when cost1 <= cost2, child2 otherwise. Return the node.
  notImplemented("DynamicAabbTree::pickSibling", "Lab 4 handout, section 10.1", box);
}

void DynamicAabbTree::refitUpward(int node) {
  // Walk to the root: balance each node, then refit its box and height from its children
  // TODO(student): while node != kNull: node = balance(node); box = enclose(children's boxes); height = 1 + max(children's heights); node = its parent.
  notImplemented("DynamicAabbTree::refitUpward", "Lab 4 handout, section 10.1", node);
}

int DynamicAabbTree::balance(int a) {
  // Find the taller child C, if it is more than one level taller than the other, B
  // TODO(student): a leaf stays; skew = height(child2) - height(child1); |skew| <= 1: return a.
  // C moves up into a's place: a's parent now points at C, and a becomes C's child
  // TODO(student): C.parent = A.parent (or root_ = C); A.parent = C. Take references into nodes_ after nothing can grow it.
  // C keeps its taller child T; a takes the shorter one S where C was
  // TODO(student): C.child1 = a, C.child2 = T; in a, replace C by S; S.parent = a.
  // Refit a first (now C's child), then C
  // TODO(student): boxes by enclose, heights 1 + max of the children's; return C.
  notImplemented("DynamicAabbTree::balance", "Lab 4 handout, section 10.1", a);
}

}  // namespace physlab
