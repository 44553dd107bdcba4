// The memory of one module's syntax tree (private to the front end): nodes
// are placed one after another in large blocks, freed together when the
// module goes. A file of 50,000 lines has about a million nodes; one
// allocation each was a good part of the parser's time.
#pragma once

#include "cncc/frontend/ast.h"

#include <cstddef>
#include <memory>
#include <new>
#include <utility>
#include <vector>

namespace cncc::frontend {

class NodeArena {
public:
  NodeArena() = default;
  NodeArena(const NodeArena&) = delete;
  NodeArena& operator=(const NodeArena&) = delete;

  template <typename Node, typename... Arguments>
  std::unique_ptr<Node, NodeDeleter> make(Arguments&&... arguments) {
    static_assert(alignof(Node) <= alignment);
    void* memory = allocate(sizeof(Node));
    return std::unique_ptr<Node, NodeDeleter>(new (memory)
                                                  Node(std::forward<Arguments>(arguments)...));
  }

  // Moves the elements of `stack` from `first` on into a list of their own
  // in the arena, and removes them from the stack (where the parser
  // collects the children of the nodes it is in).
  template <typename Element>
  NodeList<Element> takeList(std::vector<Element>& stack, std::size_t first) {
    static_assert(alignof(Element) <= alignment);
    std::size_t size = stack.size() - first;
    if (size == 0) {
      return {};
    }
    auto* elements = static_cast<Element*>(allocate(size * sizeof(Element)));
    std::uninitialized_move(stack.begin() + static_cast<std::ptrdiff_t>(first), stack.end(),
                            elements);
    stack.resize(first);
    return NodeList<Element>(elements, size);
  }

private:
  // Every node's members are at most pointers and doubles; a larger
  // alignment would pad the small nodes.
  static constexpr std::size_t alignment = alignof(double) > alignof(void*) ? alignof(double)
                                                                            : alignof(void*);
  static constexpr std::size_t blockSize = 64 * 1024;

  void* allocate(std::size_t size) {
    size = (size + alignment - 1) / alignment * alignment;
    if (size > available_) {
      newBlock(size);
    }
    void* memory = next_;
    next_ += size;
    available_ -= size;
    return memory;
  }

  // Out of line: allocate() is inlined into every node's construction.
  [[gnu::noinline]] void newBlock(std::size_t size) {
    std::size_t bytes = size > blockSize ? size : blockSize;
    // Not zeroed: every node is constructed in place.
    blocks_.push_back(std::unique_ptr<Storage[]>(new Storage[bytes / alignment]));
    next_ = reinterpret_cast<std::byte*>(blocks_.back().get());
    available_ = bytes;
  }

  struct alignas(alignment) Storage {
    std::byte bytes[alignment];
  };
  std::vector<std::unique_ptr<Storage[]>> blocks_;
  std::byte* next_ = nullptr;
  std::size_t available_ = 0;
};

} // namespace cncc::frontend
