#include "gl_thread.hpp"

#include <utility>

namespace arbor::glraycast {

GlThread::GlThread()
{
    thread_ = std::thread([this] { loop(); });
    std::unique_lock lock(mutex_);
    done_.wait(lock, [&] { return started_; });
    if (failure_) {
        lock.unlock();
        thread_.join();
        std::rethrow_exception(failure_);
    }
}

GlThread::~GlThread()
{
    if (!thread_.joinable())
        return;
    {
        std::lock_guard lock(mutex_);
        stop_ = true;
    }
    wake_.notify_one();
    thread_.join();
}

void GlThread::run(const std::function<void()> &job)
{
    std::unique_lock lock(mutex_);
    job_ = &job;
    finished_ = false;
    failure_ = nullptr;
    wake_.notify_one();
    done_.wait(lock, [&] { return finished_; });
    job_ = nullptr;
    if (failure_)
        std::rethrow_exception(std::exchange(failure_, nullptr));
}

void GlThread::loop()
{
    {
        std::lock_guard lock(mutex_);
        try {
            context_ = std::make_unique<EglContext>();
        } catch (...) {
            failure_ = std::current_exception();
            started_ = true;
            done_.notify_one();
            return;
        }
        started_ = true;
    }
    done_.notify_one();
    std::unique_lock lock(mutex_);
    for (;;) {
        wake_.wait(lock, [&] { return stop_ || (job_ && !finished_); });
        if (stop_ && !(job_ && !finished_))
            break;
        const std::function<void()> *job = job_;
        lock.unlock();
        std::exception_ptr failure;
        try {
            (*job)();
        } catch (...) {
            failure = std::current_exception();
        }
        lock.lock();
        failure_ = failure;
        finished_ = true;
        done_.notify_one();
    }
    lock.unlock();
    context_.reset(); // destroyed on the thread it is current on
}

} // namespace arbor::glraycast
