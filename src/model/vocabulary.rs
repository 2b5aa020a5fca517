//! Type checking across the agent, the PDDL domain and the manifest.
