//! Closed-form contact laws: the three-phase collision model of Li, Yang & Shi (2019).
