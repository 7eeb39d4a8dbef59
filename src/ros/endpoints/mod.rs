//! The node's endpoints: [`table::ENDPOINTS`] declares each topic and service once;
//! [`Names`] holds the names a running node gave them.

#[cfg(test)]
mod docs_table;
mod live_kinds;
mod names;
pub(crate) mod table;

pub(crate) use live_kinds::{InputTopic, Service};
pub(crate) use names::Names;
pub(crate) use table::{spec_of, Direction, Endpoint, Live, Outlet, Qos, When, ENDPOINTS, OUTLETS};
