//! The node's endpoints: [`table::ENDPOINTS`] declares each topic and service once;
//! [`Names`] holds the names a running node gave them.

#[cfg(test)]
pub(crate) mod docs_table;
mod names;
pub(crate) mod table;

pub(crate) use names::Names;
pub(crate) use table::{
    endpoint_list, spec_of, Direction, Endpoint, Live, Outlet, Qos, Service, When, ENDPOINTS,
    OUTLETS,
};
