//! Symmetry over instances of one agent (`pinger #3` in a `.mas2j`, `instances = 3` in an
//! `[[agent]]`): agents that run one plan library are interchangeable when nothing tells
//! them apart but their names, so renaming them maps runs of the system to runs. The search
//! then stores one state per class of states equal up to such a renaming, under the
//! fingerprint of a canonical member of the class ([`Instances::fingerprint`]).
//!
//! A renaming of agents permutes their states and mailboxes, and renames what names them:
//! their names in terms (`source(pinger2)`, what `.my_name` gave, message contents), the
//! atoms of the environment and of every agent's beliefs whose arguments are agents
//! (`ponged(pinger2)`, when the agents are objects too), the senders of messages and of
//! told beliefs.
//!
//! The canonical member: each instance gets a signature that renaming carries along (its
//! own state and mailbox with every instance's name collapsed into one, where the other
//! agents first name it, the atoms that name it alone); instances are sorted by it, and
//! only ties between instances that are not interchangeable in the state are tried in
//! every order (at most [`MAX_TIE_ORDERS`]), keeping the least fingerprint. Whatever the
//! outcome, a stored state is a renaming of a real one, so a less than perfect canonical
//! form costs reduction only, never soundness.
//!
//! Soundness needs the system to treat the instances alike: [`Instances::new`] leaves out
//! a group (symmetry off for it, and says why) whose names are written in a plan library
//! or the PDDL domain (`.send(pinger1, ...)`), in a request, in a checked condition that is
//! not symmetric in them (`ponged(pinger1) & ponged(pinger2)` is, with two instances;
//! `pinger1::x` alone is not), or whose renaming turns an initial state into one that is
//! not initial. Where the reasoning cycle itself tells names apart (Jason perceives several
//! changes in the hash order of their names, and lists a belief's sources sorted by name),
//! the equivariance check ([`Instances::equivariance_violation`]) finds it at the stored
//! states and the report says so.

use super::rename::{rename_names, rename_state, Rename};
use super::soundness::{normal, words};
use super::{mix, next_arrangement};
use crate::check::explore::fingerprint;
use crate::model::atoms::AtomId;
use crate::model::cond::Cond;
use crate::model::formula::agent_stride;
use crate::model::term::Term;
use crate::model::universe::ObjectId;
use crate::semantics::{Message, Step, System, SystemState};
use std::cell::RefCell;
use std::collections::{HashMap, HashSet};
use std::sync::Arc;

/// Most orders tried to break ties between instances that are not interchangeable; beyond
/// it the sorted order is kept as it is (less reduction, still sound).
pub const MAX_TIE_ORDERS: usize = 120;

/// A renaming of agents: agent index -> agent index (every agent outside the groups maps
/// to itself).
pub type AgentPerm = Vec<u8>;

/// The groups of interchangeable agents of a system and what renaming them needs.
pub struct Instances {
    /// Each group's agents, in index order (two or more).
    groups: Vec<Vec<u8>>,
    /// Agent index -> its group, if it is in one.
    group_of: Vec<Option<u16>>,
    /// Agent index -> its name (as an atom term).
    names: Vec<Arc<str>>,
    /// The name of each agent in a group -> its index.
    by_name: HashMap<Arc<str>, u8>,
    /// Agent index -> the object of its name, when the name is an object of the universe.
    objects: Vec<Option<ObjectId>>,
    /// Per atom: its arguments that are agents of a group, as (stride, parameter type,
    /// agent).
    atom_args: Vec<Vec<(u32, u16, u8)>>,
    /// Parameter type -> agent -> the agent's object's position among the type's objects.
    position: Vec<Vec<u32>>,
    atom_count: usize,
    /// The atoms of one agent's beliefs in a condition over every agent
    /// ([`System::everything`]).
    stride: usize,
    /// The agents in no group.
    fixed: Vec<u8>,
    /// Each group as the report names it: its agents and their plan library.
    described: Vec<String>,
    /// The groups of instances left out, each with why (for the report).
    pub refused: Vec<String>,
}

/// A renaming of agents acting on the parts of agent states ([`rename_state`]); a map
/// that is not one to one (every instance of a group to the first) collapses them.
struct Renamer<'a> {
    inst: &'a Instances,
    perm: &'a [u8],
}

impl Rename for Renamer<'_> {
    fn rename(&self, t: &Term) -> Option<Term> {
        rename_names(t, &|n| {
            let &k = self.inst.by_name.get(n)?;
            let image = self.perm[k as usize];
            (image != k).then(|| self.inst.names[image as usize].clone())
        })
    }

    fn atom(&self, a: AtomId) -> AtomId {
        self.inst.atom_image(a, self.perm)
    }

    fn atom_count(&self) -> usize {
        self.inst.atom_count
    }

    fn agents(&self, bits: u64) -> u64 {
        let mut out = 0u64;
        for (k, &image) in self.perm.iter().enumerate() {
            if bits >> k & 1 == 1 {
                out |= 1 << image;
            }
        }
        out
    }
}

/// Records the agents of a group named in the terms of an agent state, in the order
/// [`rename_state`] meets them (events, intentions, the pending and waiting ones: an order
/// renaming keeps), renaming nothing.
struct Occurrences<'a> {
    inst: &'a Instances,
    seen: RefCell<Vec<u8>>,
}

impl Rename for Occurrences<'_> {
    fn rename(&self, t: &Term) -> Option<Term> {
        self.inst.members_in(t, &mut self.seen.borrow_mut());
        None
    }

    fn atom(&self, a: AtomId) -> AtomId {
        a
    }

    fn atom_count(&self) -> usize {
        self.inst.atom_count
    }
}

/// What separates the instances of a group in one state: sorted by it, renamings of a state
/// give the same order (see the module documentation).
#[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Debug)]
struct Signature {
    /// Where the agents outside the groups first name the instance (`u32::MAX`: nowhere).
    first: u32,
    /// The instance's own state and mailbox, every instance's name collapsed into one.
    own: u64,
    /// A sum over what names the instance alone: atoms of the environment and of the other
    /// agents' beliefs, who told what, messages it sent.
    named: u64,
}

impl Instances {
    /// The groups of interchangeable agents of `system`: the agents that run one plan
    /// library, but the first agent when the user makes requests (they go to it), with
    /// `conds` the checked conditions (over [`System::everything`]). A group whose names
    /// something tells apart is left out, with why ([`Instances::refused`]).
    pub fn new(system: &System, conds: &[(&str, &Cond)]) -> Instances {
        let projects: Vec<_> = system.agents.iter().map(|s| s.project).collect();
        let skip_first = !system.agents[0].requests.is_empty();
        let mut groups: Vec<Vec<u8>> = Vec::new();
        for (k, p) in projects.iter().enumerate() {
            if k == 0 && skip_first {
                continue;
            }
            let file = &p.manifest.agent.plans.path;
            match groups
                .iter_mut()
                .find(|g| projects[g[0] as usize].manifest.agent.plans.path == *file)
            {
                Some(g) => g.push(k as u8),
                None => groups.push(vec![k as u8]),
            }
        }
        groups.retain(|g| g.len() > 1);
        let all = Instances::build(system, groups.clone());
        let mut refused = Vec::new();
        let mut kept = Vec::new();
        for (i, g) in groups.into_iter().enumerate() {
            match all.refusal(system, i, conds) {
                Some(why) => refused.push(format!(
                    "symmetry over the instances {} is off: {why}, so renaming them could change what the system does",
                    all.described[i]
                )),
                None => kept.push(g),
            }
        }
        let mut out = Instances::build(system, kept);
        out.refused = refused;
        out
    }

    fn build(system: &System, groups: Vec<Vec<u8>>) -> Instances {
        let project = system.agents[0].project;
        let u = &project.universe;
        let atoms = &project.atoms;
        let n = system.agents.len();
        let names: Vec<Arc<str>> = system.names().iter().map(|s| Arc::from(&**s)).collect();
        let mut group_of = vec![None; n];
        for (i, g) in groups.iter().enumerate() {
            for &k in g {
                group_of[k as usize] = Some(i as u16);
            }
        }
        let by_name = (0..n)
            .filter(|&k| group_of[k].is_some())
            .map(|k| (names[k].clone(), k as u8))
            .collect();
        let objects: Vec<Option<ObjectId>> = (0..n)
            .map(|k| group_of[k].and_then(|_| u.object(&names[k])))
            .collect();
        let agent_of: HashMap<ObjectId, u8> = objects
            .iter()
            .enumerate()
            .filter_map(|(k, o)| o.map(|o| (o, k as u8)))
            .collect();
        let position: Vec<Vec<u32>> = (0..u.type_count())
            .map(|t| {
                let members = u.objects_of(crate::model::universe::TypeId(t as u16));
                objects
                    .iter()
                    .map(|o| {
                        o.and_then(|o| members.iter().position(|m| *m == o))
                            .map_or(u32::MAX, |p| p as u32)
                    })
                    .collect()
            })
            .collect();
        let mut atom_args = Vec::with_capacity(atoms.len());
        for a in 0..atoms.len() as u32 {
            let mut list = Vec::new();
            if !agent_of.is_empty() {
                let (p, args) = atoms.decode(AtomId(a));
                let params = atoms.pred_params(p);
                let mut stride = 1u32;
                for i in (0..args.len()).rev() {
                    if let Some(&k) = agent_of.get(&args[i]) {
                        list.push((stride, params[i].0, k));
                    }
                    stride *= u.objects_of(params[i]).len() as u32;
                }
            }
            atom_args.push(list);
        }
        let described = groups
            .iter()
            .map(|g| {
                let members: Vec<String> = g
                    .iter()
                    .map(|&k| format!("`{}`", names[k as usize]))
                    .collect();
                let file = project_file(system, g[0]);
                format!("{} (of `{file}`)", members.join(", "))
            })
            .collect();
        Instances {
            fixed: (0..n as u8)
                .filter(|&k| group_of[k as usize].is_none())
                .collect(),
            groups,
            group_of,
            names,
            by_name,
            objects,
            atom_args,
            position,
            atom_count: atoms.len(),
            stride: agent_stride(atoms),
            described,
            refused: Vec::new(),
        }
    }

    /// Whether no group is left: no two agents are interchangeable, and symmetry reduces
    /// nothing.
    pub fn is_empty(&self) -> bool {
        self.groups.is_empty()
    }

    /// The groups, as the report names them, with their sizes.
    pub fn describe(&self) -> Vec<(String, usize)> {
        self.described
            .iter()
            .zip(&self.groups)
            .map(|(d, g)| (d.clone(), g.len()))
            .collect()
    }

    /// Whether agents `a` and `b` are one agent or instances of one group.
    pub fn alike(&self, a: u8, b: u8) -> bool {
        a == b
            || self.group_of[a as usize].is_some()
                && self.group_of[a as usize] == self.group_of[b as usize]
    }

    /// Why group `i` must be left out, if it must.
    fn refusal(&self, system: &System, i: usize, conds: &[(&str, &Cond)]) -> Option<String> {
        let g = &self.groups[i];
        let project = system.agents[0].project;
        let named = |w: &str, pddl: bool| {
            g.iter().map(|&k| &self.names[k as usize]).find(|n| {
                if pddl {
                    n.eq_ignore_ascii_case(w)
                } else {
                    &***n == w
                }
            })
        };
        // A told plan's source names its sender, which a renaming would have to follow.
        let told = system.agents.iter().any(|a| {
            a.project
                .plans
                .changes
                .as_ref()
                .is_some_and(|c| !c.told.is_empty())
        });
        if told && !g.is_empty() {
            return Some(
                "the agents tell each other plans (`tellHow`, `askHow`), whose sources name them"
                    .into(),
            );
        }
        // The agents' objects, if they are objects: all of one type, or none.
        let types: HashSet<Option<_>> = g
            .iter()
            .map(|&k| self.objects[k as usize].map(|o| project.universe.object_type(o)))
            .collect();
        if types.len() > 1 {
            return Some("some of their names are objects of the PDDL model and some are not, or are of different types".into());
        }
        for f in project.map.files() {
            let pddl = match f.path.extension().and_then(|e| e.to_str()) {
                Some("asl") => false,
                Some("pddl") => true,
                _ => continue,
            };
            for (start, w) in words(&f.text, pddl) {
                if let Some(n) = named(w, pddl) {
                    let span = crate::syntax::Span::new(f.id, start, start + w.len());
                    let at = project.map.location(span);
                    return Some(format!("{}:{}:{} names `{n}`", at.file, at.line, at.column));
                }
            }
        }
        for r in &system.agents[0].requests {
            let mut found = Vec::new();
            self.members_in(r, &mut found);
            if let Some(&k) = found.iter().find(|k| g.contains(k)) {
                return Some(format!(
                    "the request `{r}` names `{}`",
                    self.names[k as usize]
                ));
            }
        }
        let gens = self.generators_of(g);
        for (name, c) in conds {
            let base = normal(c, &|a| a);
            if gens
                .iter()
                .any(|p| normal(c, &|a| self.everything_image(a, p)) != base)
            {
                return Some(format!("`{name}` is not symmetric in them"));
            }
        }
        let initial: HashSet<&crate::model::atoms::AtomSet> =
            project.initial.states().iter().collect();
        let open = project.initial.states().iter().any(|w| {
            gens.iter().any(|p| {
                let mut img = crate::model::atoms::AtomSet::empty(self.atom_count);
                w.iter().for_each(|a| img.insert(self.atom_image(a, p)));
                !initial.contains(&img)
            })
        });
        if open {
            return Some(
                "renaming them turns an initial state of the environment into one that is not initial"
                    .into(),
            );
        }
        None
    }

    /// Appends the agents of a group named in `t` (each once).
    fn members_in(&self, t: &Term, out: &mut Vec<u8>) {
        match t {
            Term::Atom(n) => {
                if let Some(&k) = self.by_name.get(n) {
                    if !out.contains(&k) {
                        out.push(k);
                    }
                }
            }
            Term::Struct(st) => {
                for a in st.args().iter().chain(st.annots()) {
                    self.members_in(a, out);
                }
            }
            Term::Cons(c) => {
                self.members_in(c.head(), out);
                self.members_in(c.tail(), out);
            }
            _ => {}
        }
    }

    /// The agents of a group named in `t`, in order of occurrence.
    pub fn named_in(&self, t: &Term) -> Vec<u8> {
        let mut out = Vec::new();
        self.members_in(t, &mut out);
        out
    }

    fn identity(&self) -> AgentPerm {
        (0..self.names.len() as u8).collect()
    }

    /// Generators of the renamings of one group: a swap of its first two agents and a
    /// rotation of all of them.
    fn generators_of(&self, g: &[u8]) -> Vec<AgentPerm> {
        let mut out = Vec::new();
        let mut swap = self.identity();
        swap.swap(g[0] as usize, g[1] as usize);
        out.push(swap);
        if g.len() > 2 {
            let mut rot = self.identity();
            for (i, &m) in g.iter().enumerate() {
                rot[m as usize] = g[(i + 1) % g.len()];
            }
            out.push(rot);
        }
        out
    }

    /// Generators of every renaming.
    pub fn generators(&self) -> Vec<AgentPerm> {
        self.groups
            .iter()
            .flat_map(|g| self.generators_of(g))
            .collect()
    }

    /// The image of an atom under a renaming (or a collapse) of agents.
    fn atom_image(&self, a: AtomId, perm: &[u8]) -> AtomId {
        let mut id = i64::from(a.0);
        for &(stride, t, k) in &self.atom_args[a.0 as usize] {
            let pos = &self.position[t as usize];
            id += i64::from(stride)
                * (i64::from(pos[perm[k as usize] as usize]) - i64::from(pos[k as usize]));
        }
        AtomId(id as u32)
    }

    /// The image of an atom of [`System::everything`] (the environment's, then each
    /// agent's beliefs) under a renaming.
    fn everything_image(&self, a: AtomId, perm: &[u8]) -> AtomId {
        let (k, b) = (a.0 as usize / self.stride, a.0 as usize % self.stride);
        let b = self.atom_image(AtomId(b as u32), perm).0 as usize;
        let k = match k {
            0 => 0,
            k => perm[k - 1] as usize + 1,
        };
        AtomId((k * self.stride + b) as u32)
    }

    /// `s` renamed by `perm`.
    pub fn apply(&self, s: &SystemState, perm: &[u8]) -> SystemState {
        let r = Renamer { inst: self, perm };
        let SystemState {
            world,
            agents,
            mail,
        } = s;
        let mut w = crate::model::atoms::AtomSet::empty(self.atom_count);
        world
            .iter()
            .for_each(|a| w.insert(self.atom_image(a, perm)));
        // Agent `perm[k]` of the image is agent `k` renamed.
        let mut from = vec![0usize; perm.len()];
        for (k, &to) in perm.iter().enumerate() {
            from[to as usize] = k;
        }
        SystemState {
            world: w,
            agents: from.iter().map(|&k| rename_state(&r, &agents[k])).collect(),
            mail: from
                .iter()
                .map(|&k| mail[k].iter().map(|m| self.message(&r, m)).collect())
                .collect(),
        }
    }

    fn message(&self, r: &Renamer, m: &Message) -> Message {
        let Message {
            from,
            performative,
            content,
            ask,
            reply_to,
        } = m;
        // An ask's id is its sender's, an answer's its receiver's: each moves with its
        // agent, unchanged.
        Message {
            from: r.perm[*from as usize],
            performative: *performative,
            content: r.rename(content).unwrap_or_else(|| content.clone()),
            ask: *ask,
            reply_to: *reply_to,
        }
    }

    /// The map that collapses every instance of a group into its first.
    fn collapse(&self) -> AgentPerm {
        let mut p = self.identity();
        for g in &self.groups {
            for &k in g {
                p[k as usize] = g[0];
            }
        }
        p
    }

    /// Each instance's signature in `s`.
    fn signatures(&self, s: &SystemState) -> Vec<Signature> {
        let n = self.names.len();
        let collapse = self.collapse();
        let c = Renamer {
            inst: self,
            perm: &collapse,
        };
        let mut sig = vec![
            Signature {
                first: u32::MAX,
                own: 0,
                named: 0,
            };
            n
        ];
        for g in &self.groups {
            for &k in g {
                let k = k as usize;
                let mail: Vec<Message> = s.mail[k].iter().map(|m| self.message(&c, m)).collect();
                sig[k].own = fingerprint(&(rename_state(&c, &s.agents[k]), mail));
            }
        }
        // Where the fixed agents first name each instance: in their terms, then in their
        // mail.
        let rec = Occurrences {
            inst: self,
            seen: RefCell::new(Vec::new()),
        };
        for &j in &self.fixed {
            let j = j as usize;
            rename_state(&rec, &s.agents[j]);
            for m in &s.mail[j] {
                let mut seen = rec.seen.borrow_mut();
                if self.group_of[m.from as usize].is_some() && !seen.contains(&m.from) {
                    seen.push(m.from);
                }
                self.members_in(&m.content, &mut seen);
            }
        }
        for (i, k) in rec.seen.into_inner().into_iter().enumerate() {
            sig[k as usize].first = i as u32;
        }
        // What names one instance alone: atoms (of the environment, tagged 0, and of each
        // agent's beliefs, tagged with the agent as its class: a fixed agent by its index,
        // an instance by its own signature), told beliefs, messages.
        let tag = |j: usize| -> u64 {
            if self.group_of[j].is_some() {
                sig[j].own | 1
            } else {
                (j as u64) << 1
            }
        };
        let mut named = vec![0u64; n];
        let atoms = |set: &crate::model::atoms::AtomSet, tag: u64, named: &mut [u64]| {
            for a in set.iter() {
                if let Some(k) = self.alone(a) {
                    let key = u64::from(self.atom_image(a, &collapse).0);
                    named[k as usize] = named[k as usize].wrapping_add(mix(key ^ mix(tag)));
                }
            }
        };
        atoms(&s.world, 0, &mut named);
        for j in 0..n {
            let t = mix(tag(j)) ^ 2;
            atoms(&s.agents[j].beliefs, t, &mut named);
            for told in &s.agents[j].told {
                let key = u64::from(self.atom_image(told.atom, &collapse).0) | 1 << 40;
                for (k, x) in named.iter_mut().enumerate() {
                    if told.from >> k & 1 == 1 && self.group_of[k].is_some() {
                        *x = x.wrapping_add(mix(key ^ mix(t)));
                    }
                }
            }
            for m in &s.mail[j] {
                let k = m.from as usize;
                if self.group_of[k].is_some() {
                    let content = c.rename(&m.content).unwrap_or_else(|| m.content.clone());
                    let key = fingerprint(&(content, m.performative)) | 1 << 41;
                    named[k] = named[k].wrapping_add(mix(key ^ mix(t)));
                }
            }
        }
        for (x, named) in sig.iter_mut().zip(named) {
            x.named = named;
        }
        sig
    }

    /// The one instance an atom names, if it names exactly one.
    fn alone(&self, a: AtomId) -> Option<u8> {
        let args = &self.atom_args[a.0 as usize];
        let &(_, _, k) = args.first()?;
        args.iter().all(|&(_, _, j)| j == k).then_some(k)
    }

    /// The renamings that may take `s` to its canonical member: the sorting order, and
    /// when instances that are not interchangeable tie, that order with every arrangement
    /// of each tie (none beyond [`MAX_TIE_ORDERS`]).
    fn candidates(&self, s: &SystemState) -> Vec<AgentPerm> {
        let sig = self.signatures(s);
        let mut perm = self.identity();
        // Ties, as the slots they fill.
        let mut ties: Vec<Vec<u8>> = Vec::new();
        for g in &self.groups {
            let mut order = g.clone();
            order.sort_by_key(|&k| (sig[k as usize], k));
            for (slot, &k) in order.iter().enumerate() {
                perm[k as usize] = g[slot];
            }
            let mut i = 0;
            while i < order.len() {
                let mut j = i + 1;
                while j < order.len() && sig[order[j] as usize] == sig[order[i] as usize] {
                    j += 1;
                }
                if j - i > 1 && !self.interchangeable(s, &order[i..j]) {
                    ties.push(g[i..j].to_vec());
                }
                i = j;
            }
        }
        let orders = ties
            .iter()
            .map(|t| (1..=t.len()).product::<usize>())
            .try_fold(1usize, |acc, k| acc.checked_mul(k))
            .unwrap_or(usize::MAX);
        if ties.is_empty() || orders > MAX_TIE_ORDERS {
            return vec![perm];
        }
        let mut out = Vec::new();
        let mut arrangement = ties.clone();
        loop {
            let mut p = perm.clone();
            for (tie, arr) in ties.iter().zip(&arrangement) {
                let mut remap = self.identity();
                for (k, &slot) in tie.iter().enumerate() {
                    remap[slot as usize] = arr[k];
                }
                p.iter_mut().for_each(|x| *x = remap[*x as usize]);
            }
            out.push(p);
            if !next_arrangement(&mut arrangement) {
                break;
            }
        }
        out
    }

    /// Whether swapping any two of `agents` leaves `s` as it is (then their order does not
    /// matter): checked for neighbours, whose swaps generate every order.
    fn interchangeable(&self, s: &SystemState, agents: &[u8]) -> bool {
        agents.windows(2).all(|w| {
            let mut p = self.identity();
            p.swap(w[0] as usize, w[1] as usize);
            self.apply(s, &p) == *s
        })
    }

    /// The canonical member of `s`'s class and its fingerprint (`None`: `s` itself).
    pub fn canonical(&self, s: &SystemState) -> (u64, Option<SystemState>) {
        let (fp, p) = self.canonical_renaming(s);
        let identity = p.iter().enumerate().all(|(i, &x)| x as usize == i);
        (fp, (!identity).then(|| self.apply(s, &p)))
    }

    /// The fingerprint of `s`'s canonical member and the renaming that takes `s` to it
    /// (agent `k` of `s` is agent `perm[k]` there).
    pub fn canonical_renaming(&self, s: &SystemState) -> (u64, AgentPerm) {
        let candidates = self.candidates(s);
        if let [p] = candidates.as_slice() {
            if p.iter().enumerate().all(|(i, &x)| x as usize == i) {
                return (fingerprint(s), p.clone());
            }
        }
        candidates
            .into_iter()
            .map(|p| (fingerprint(&self.apply(s, &p)), p))
            .min_by_key(|(fp, _)| *fp)
            .expect("at least one candidate")
    }

    /// The fingerprint `s` is stored under: its canonical member's.
    pub fn fingerprint(&self, s: &SystemState) -> u64 {
        self.canonical_renaming(s).0
    }

    /// Whether the system treats the instances alike at `s`: for each generator `g` of
    /// the renamings, the successors of `g(s)` are renamings of the successors of `s`
    /// (each the renaming by `g`, or else as multisets of classes). `None` when it holds,
    /// otherwise the renaming that breaks it, as agent names.
    pub fn equivariance_violation(&self, system: &System, s: &SystemState) -> Option<String> {
        let succ: Vec<SystemState> = system.successors(s).into_iter().map(|(_, t)| t).collect();
        let mut classes: Option<Vec<u64>> = None;
        self.generators().into_iter().find_map(|g| {
            let other: Vec<SystemState> = system
                .successors(&self.apply(s, &g))
                .into_iter()
                .map(|(_, t)| t)
                .collect();
            let mut renamed: Vec<u64> = succ
                .iter()
                .map(|t| fingerprint(&self.apply(t, &g)))
                .collect();
            let mut theirs: Vec<u64> = other.iter().map(fingerprint).collect();
            renamed.sort_unstable();
            theirs.sort_unstable();
            if renamed == theirs {
                return None;
            }
            let here = classes.get_or_insert_with(|| {
                let mut v: Vec<u64> = succ.iter().map(|t| self.fingerprint(t)).collect();
                v.sort_unstable();
                v
            });
            let mut there: Vec<u64> = other.iter().map(|t| self.fingerprint(t)).collect();
            there.sort_unstable();
            (*here != there).then(|| self.show(&g))
        })
    }

    /// A renaming as the agents it moves, `a -> b`.
    pub fn show(&self, perm: &[u8]) -> String {
        perm.iter()
            .enumerate()
            .filter(|(i, &j)| *i != j as usize)
            .map(|(i, &j)| format!("{} -> {}", self.names[i], self.names[j as usize]))
            .collect::<Vec<_>>()
            .join(", ")
    }

    /// The renamings that map `involved` (agents of groups, distinct) one to one into their
    /// groups, each extended to every agent (the others of each group in order): one
    /// renaming per image of `involved`, the identity first.
    pub fn images(&self, involved: &[u8]) -> Vec<AgentPerm> {
        let involved: Vec<u8> = involved
            .iter()
            .copied()
            .filter(|&k| self.group_of[k as usize].is_some())
            .collect();
        let mut out = Vec::new();
        let mut chosen: Vec<u8> = Vec::new();
        self.extend_images(&involved, &mut chosen, &mut out);
        out
    }

    fn extend_images(&self, involved: &[u8], chosen: &mut Vec<u8>, out: &mut Vec<AgentPerm>) {
        let i = chosen.len();
        if i == involved.len() {
            let mut p = self.identity();
            for g in &self.groups {
                let mut rest_from = g.iter().filter(|k| !involved.contains(k));
                let mut rest_to = g.iter().filter(|k| !chosen.contains(k));
                for &k in g {
                    if let Some(at) = involved.iter().position(|&x| x == k) {
                        p[k as usize] = chosen[at];
                    }
                }
                while let (Some(&a), Some(&b)) = (rest_from.next(), rest_to.next()) {
                    p[a as usize] = b;
                }
            }
            out.push(p);
            return;
        }
        let k = involved[i];
        let g = &self.groups[self.group_of[k as usize].expect("in a group") as usize];
        // The identity first: `k` itself, then the others in order.
        let targets = std::iter::once(k).chain(g.iter().copied().filter(|&x| x != k));
        for t in targets {
            if chosen.contains(&t) {
                continue;
            }
            chosen.push(t);
            self.extend_images(involved, chosen, out);
            chosen.pop();
        }
    }

    /// The run `states`/`steps` renamed by `perm`, followed in the system: from the
    /// renamed initial state (an initial state), each step the successor that is the
    /// renamed next state, taken by the renamed agent. `None` where there is none (the
    /// system does not treat the instances alike there).
    pub fn rename_run(
        &self,
        system: &System,
        states: &[SystemState],
        steps: &[Step],
        perm: &[u8],
    ) -> Option<(Vec<SystemState>, Vec<Step>)> {
        let start = self.apply(states.first()?, perm);
        if !system.initial_states().contains(&start) {
            return None;
        }
        let mut out_states = vec![start];
        let mut out_steps = Vec::new();
        for (next, step) in states[1..].iter().zip(steps) {
            let want = self.apply(next, perm);
            let agent = perm[step.agent as usize];
            let (label, t) = system
                .successors(out_states.last().expect("a state"))
                .into_iter()
                .find(|(l, t)| l.agent == agent && *t == want)?;
            out_states.push(t);
            out_steps.push(label);
        }
        Some((out_states, out_steps))
    }
}

/// The file an agent's plans are read from, as the report names it.
fn project_file(system: &System, k: u8) -> String {
    let p = system.agents[k as usize].project;
    let path = &p.manifest.agent.plans.path;
    p.map
        .find_path(path)
        .and_then(|id| p.map.files().iter().find(|f| f.id == id))
        .map_or_else(|| path.display().to_string(), |f| f.name.clone())
}
