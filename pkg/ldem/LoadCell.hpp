// A load cell's reading at a record: the mean of a group's stress over the
// states since the last record and this one, i.e. the impulse through the
// group over the record interval, over the interval; never one step's sample
// (the top of the ringing).
#pragma once

namespace ldem {

class LoadCell {
public:
    void restart() { sum_ = 0, states_ = 0; }  // a new record interval
    void add(double stress) { sum_ += stress, ++states_; }  // a state of the interval before its record's
    double reading(double now) const { return (sum_ + now) / (states_ + 1); }  // now: the record's state

private:
    double sum_ = 0;
    int states_ = 0;
};

}  // namespace ldem
