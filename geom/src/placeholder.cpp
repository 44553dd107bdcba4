namespace cncc::geom {}
