//! Program control: CALL, RET/CRET, END, STOP, watchdog, fatal errors.
