//! The resolved names of the endpoints a node made (namespace, node name and remapping
//! applied), one list for the recording, the live view and the start-up line.

use super::table::{spec_of, Endpoint, EndpointSpec, ENDPOINTS};

/// One endpoint as made: its entry, which instance (the k-th muscle topic) and its name.
#[derive(Debug, Clone)]
pub(crate) struct Resolved {
    pub(crate) endpoint: Endpoint,
    /// The k-th of a per-muscle endpoint (0 otherwise).
    pub(crate) k: usize,
    pub(crate) name: String,
}

impl Resolved {
    pub(crate) fn spec(&self) -> &'static EndpointSpec {
        spec_of(self.endpoint)
    }

    /// The recording's channel of this instance, if it is recorded.
    pub(crate) fn channel(&self) -> Option<(Endpoint, usize)> {
        self.spec().record.then_some((self.endpoint, self.k))
    }
}

/// The endpoints a node has, with their resolved names.
#[derive(Debug, Clone, Default)]
pub(crate) struct Names {
    made: Vec<Resolved>,
}

impl Names {
    /// Notes `endpoint` (its `k`-th instance) as made under `name`.
    pub(crate) fn add(&mut self, endpoint: Endpoint, k: usize, name: String) {
        self.made.push(Resolved { endpoint, k, name });
    }

    /// The name of `endpoint` (its first instance), if made.
    pub(crate) fn get(&self, endpoint: Endpoint) -> Option<&str> {
        self.made
            .iter()
            .find(|r| r.endpoint == endpoint)
            .map(|r| r.name.as_str())
    }

    /// The name of `endpoint`, or "" when not made.
    pub(crate) fn name(&self, endpoint: Endpoint) -> &str {
        self.get(endpoint).unwrap_or_default()
    }

    /// Every instance made, in [`ENDPOINTS`]' order (instances in the order made).
    pub(crate) fn in_table_order(&self) -> Vec<&Resolved> {
        ENDPOINTS
            .iter()
            .flat_map(|s| self.made.iter().filter(move |r| r.endpoint == s.endpoint))
            .collect()
    }
}
