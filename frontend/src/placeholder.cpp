namespace cncc::frontend {}
