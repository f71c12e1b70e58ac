"""Process plumbing, neither intake nor control: C loops built and cached, our threads named,
stop signals, and what native code prints while the app owns the terminal."""
