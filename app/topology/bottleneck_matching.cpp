#include "bottleneck_matching.hpp"

#include <algorithm>

namespace arbor::topology {

BottleneckMatching::BottleneckMatching(std::span<const PlanePoint> a, std::span<const PlanePoint> b)
    : a_(a.begin(), a.end()), b_(b.begin(), b.end()), a_tree_(a_), b_tree_(b_)
{
}

bool BottleneckMatching::perfect_at(double t)
{
    t_ = t;
    const std::size_t left = a_.size() + b_.size();
    mate_left_.assign(left, kNone);
    mate_right_.assign(left, kNone);
    // A point too far from the diagonal needs a point of the other diagram
    // within t: without one no matching exists (the common case below the
    // answer, found without a single augmenting search).
    b_tree_.revive_all();
    for (std::size_t i = 0; i < a_.size(); ++i)
        if (!light_a(i) && b_tree_.find_alive_within(a_[i], t) == PlanePointTree::npos)
            return false;
    for (std::size_t j = 0; j < b_.size(); ++j)
        if (!light_b(j) && a_tree_.find_alive_within(b_[j], t) == PlanePointTree::npos)
            return false;
    greedy();
    while (layer_graph())
        augment_along_layers();
    return std::none_of(mate_left_.begin(), mate_left_.end(), [](int v) { return v == kNone; });
}

std::size_t BottleneckMatching::off_diagonal_pairs() const
{
    std::size_t n = 0;
    for (std::size_t i = 0; i < a_.size(); ++i)
        n += mate_left_[i] != kNone && right_is_point(mate_left_[i]);
    return n;
}

void BottleneckMatching::greedy()
{
    const auto match = [&](int u, int v) {
        mate_left_[u] = v;
        mate_right_[v] = u;
    };
    const int na = static_cast<int>(a_.size());
    b_tree_.revive_all();
    // Far points first take a point within t; near ones their own copy.
    for (std::size_t i = 0; i < a_.size(); ++i) {
        if (light_a(i))
            continue;
        const std::size_t pos = b_tree_.find_alive_within(a_[i], t_);
        if (pos != PlanePointTree::npos) {
            match(static_cast<int>(i), static_cast<int>(b_tree_.id(pos)));
            b_tree_.remove(pos);
        }
    }
    for (std::size_t i = 0; i < a_.size(); ++i)
        if (light_a(i))
            match(static_cast<int>(i), right_of_copy(i));
    std::size_t copy = 0;
    for (std::size_t j = 0; j < b_.size(); ++j) {
        const int u = na + static_cast<int>(j);
        if (light_b(j) && mate_right_[j] == kNone) {
            match(u, static_cast<int>(j));
            continue;
        }
        while (copy < a_.size() && mate_right_[right_of_copy(copy)] != kNone)
            ++copy;
        if (copy < a_.size())
            match(u, right_of_copy(copy++));
    }
}

bool BottleneckMatching::layer_graph()
{
    const int na = static_cast<int>(a_.size());
    right_layer_.assign(mate_right_.size(), -1);
    b_tree_.revive_all();
    layers_.clear();
    std::vector<int> current;
    for (std::size_t u = 0; u < mate_left_.size(); ++u)
        if (mate_left_[u] == kNone)
            current.push_back(static_cast<int>(u));
    if (current.empty())
        return false;

    std::size_t unreached_copy = 0; // a'_i before it are reached
    bool found = false;
    while (!current.empty() && !found) {
        const int k = static_cast<int>(layers_.size());
        std::vector<uint32_t> b_ids;
        std::vector<int> copies, next;
        const auto reach = [&](int v) {
            right_layer_[v] = k;
            if (right_is_point(v))
                b_ids.push_back(static_cast<uint32_t>(v));
            else
                copies.push_back(v);
            if (mate_right_[v] == kNone)
                found = true;
            else
                next.push_back(mate_right_[v]);
        };
        for (int u : current) {
            if (left_is_point(u)) {
                const std::size_t i = static_cast<std::size_t>(u);
                if (light_a(i) && right_layer_[right_of_copy(i)] < 0)
                    reach(right_of_copy(i));
                // Points reached through their own copy stay in the tree
                // until a query meets them.
                for (std::size_t pos; (pos = b_tree_.find_alive_within(a_[i], t_)) != PlanePointTree::npos;) {
                    b_tree_.remove(pos);
                    const int v = static_cast<int>(b_tree_.id(pos));
                    if (right_layer_[v] < 0)
                        reach(v);
                }
            } else {
                const std::size_t j = static_cast<std::size_t>(u - na);
                if (light_b(j) && right_layer_[j] < 0)
                    reach(static_cast<int>(j));
                for (; unreached_copy < a_.size(); ++unreached_copy)
                    if (right_layer_[right_of_copy(unreached_copy)] < 0)
                        reach(right_of_copy(unreached_copy));
            }
        }
        if (found) {
            // The augmenting search ends only at free vertices of the last layer.
            std::erase_if(b_ids, [&](uint32_t v) { return mate_right_[v] != kNone; });
            std::erase_if(copies, [&](int v) { return mate_right_[v] != kNone; });
        }
        Layer layer;
        layer.b_points = PlanePointTree(b_, b_ids);
        layer.a_copies = std::move(copies);
        layers_.push_back(std::move(layer));
        current = std::move(next);
    }
    return found;
}

int BottleneckMatching::take_in_layer(int u, std::size_t j)
{
    Layer &layer = layers_[j];
    const bool last = j + 1 == layers_.size();
    const auto own_copy_free = [&](int v) {
        return right_layer_[v] == static_cast<int>(j) && !taken_[v] && (!last || mate_right_[v] == kNone);
    };
    if (left_is_point(u)) {
        const std::size_t i = static_cast<std::size_t>(u);
        const int copy = right_of_copy(i);
        if (light_a(i) && own_copy_free(copy)) {
            taken_[copy] = 1;
            return copy;
        }
        for (std::size_t pos; (pos = layer.b_points.find_alive_within(a_[i], t_)) != PlanePointTree::npos;) {
            layer.b_points.remove(pos);
            const int v = static_cast<int>(layer.b_points.id(pos));
            if (!taken_[v]) {
                taken_[v] = 1;
                return v;
            }
        }
        return kNone;
    }
    const int jb = u - static_cast<int>(a_.size());
    if (light_b(static_cast<std::size_t>(jb)) && own_copy_free(jb)) {
        taken_[jb] = 1;
        return jb;
    }
    while (layer.next_copy < layer.a_copies.size()) {
        const int v = layer.a_copies[layer.next_copy++];
        if (!taken_[v]) {
            taken_[v] = 1;
            return v;
        }
    }
    return kNone;
}

void BottleneckMatching::augment_along_layers()
{
    taken_.assign(mate_right_.size(), 0);
    const std::size_t last = layers_.size() - 1;
    std::vector<int> path_left, path_right;
    for (std::size_t u0 = 0; u0 < mate_left_.size(); ++u0) {
        if (mate_left_[u0] != kNone)
            continue;
        path_left.assign(1, static_cast<int>(u0));
        path_right.clear();
        while (!path_left.empty()) {
            const std::size_t depth = path_left.size() - 1;
            const int v = take_in_layer(path_left.back(), depth);
            if (v == kNone) {
                path_left.pop_back();
                if (!path_right.empty())
                    path_right.pop_back();
                continue;
            }
            path_right.push_back(v);
            if (depth == last) {
                for (std::size_t s = 0; s < path_left.size(); ++s) {
                    mate_left_[path_left[s]] = path_right[s];
                    mate_right_[path_right[s]] = path_left[s];
                }
                break;
            }
            path_left.push_back(mate_right_[v]);
        }
    }
}

} // namespace arbor::topology
