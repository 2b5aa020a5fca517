//! Explanations: the paper's two algorithms as pure functions a robot can call at run time.
//!
//! * [`demand`]: Algorithm 1, *when* to explain. Each user has a relation `N` of expected
//!   successors ([`ExpectedSuccessors`]); an executed action whose pair with the previous
//!   observation matches nothing in `N` is surprising, needs an explanation, and is learned.
//! * [`content`](mod@content): Algorithm 2, *what* to explain. The context literals of every
//!   plan on the intention stack (`Γ`), and the actions of the current plan from the
//!   explained one up to the first that modifies `Γ`: the intention behind it.
//! * [`render`]: the content as one English sentence.
//! * [`agent`]: the algorithms bound to a loaded project (its users, its phrases, the
//!   intention stack an action of the reasoning cycle ran in), shared by `explain` and the
//!   explanation properties of `verify`.
//!
//! The algorithms are keyed on ground [`Term`](crate::model::Term)s: apart from [`agent`],
//! which reads the reasoning cycle's intention stacks, the module knows nothing of the
//! reasoning cycle or the model checker, which call it with what a run observed and a
//! snapshot of the intention.
//!
//! # The paper's running example
//!
//! The owner asked the robot to store a used cup; they expect it to go to the table first
//! and pick the cup up there. The robot goes to the dishwasher instead: its plan
//! `storeUsedCup` first opens the dishwasher when it is closed and the robot's hands are free
//! (subgoal `openDishwasherIfNeed`). That is the surprising action, and its explanation names
//! the context that made the robot do it and the action it leads to.
//!
//! ```
//! use bdi_check::explain::{
//!     content, demand_over, sentence, ContextLiteral, Effects, ExpectedSuccessors,
//!     FrameSnapshot, Observation, Pair, Phrases, PlanStep, Syntactic,
//! };
//! use bdi_check::model::{term_from_expr, Substitution, Term, Var};
//! use bdi_check::syntax::{parse_expr, FileId};
//!
//! let t = |s: &str| term_from_expr(&parse_expr(FileId(0), s).unwrap()).unwrap();
//! let obs = |s: &str| Observation::parse(s).unwrap();
//!
//! // Algorithm 1: the owner's N, and what they see.
//! let mut n = ExpectedSuccessors::new([
//!     Pair::parse("!storeCup(C)", "navigateTo(table)").unwrap(),
//!     Pair::parse("navigateTo(table)", "pickUp(C)").unwrap(),
//! ]);
//! let seen = [
//!     "!storeCup(cup1)", "navigateTo(dishwasher)", "openDoor(dishwasher)",
//!     "navigateTo(table)", "pickUp(cup1)",
//! ]
//! .map(obs);
//! let due = demand_over(&mut n, &seen);
//! // The request needs nothing; going to the dishwasher (instead of the table) is
//! // surprising, and so is opening it and coming back; picking the cup up at the table is
//! // what the owner expected.
//! assert_eq!(due, [false, true, true, true, false]);
//! // N learned exactly the three surprising pairs.
//! assert_eq!(n.learned().len(), 3);
//! assert!(n.is_expected(Some(&seen[0]), &seen[1]));
//!
//! // Algorithm 2, at navigateTo(dishwasher): the intention stack, bottom first.
//! let mut c_is_cup1 = Substitution::new();
//! c_is_cup1.bind(Var::named("C"), t("cup1"));
//! let store_used_cup = FrameSnapshot {
//!     context: vec![ContextLiteral::positive(t("used(C)"))],
//!     bindings: c_is_cup1,
//!     body: vec![
//!         PlanStep::Subgoal(t("openDishwasherIfNeed")), // the step it waits on
//!         PlanStep::Action(t("navigateTo(table)")),
//!         PlanStep::Action(t("pickUp(C)")),
//!         PlanStep::Action(t("navigateTo(dishwasher)")),
//!         PlanStep::Action(t("putDown(C)")),
//!     ],
//! };
//! let open_dishwasher_if_need = FrameSnapshot {
//!     context: vec![
//!         ContextLiteral::negative(t("dishwasherDoor(open)")),
//!         ContextLiteral::positive(t("holding(none)")),
//!     ],
//!     bindings: Substitution::new(),
//!     body: vec![
//!         PlanStep::Action(t("navigateTo(dishwasher)")), // the action being explained
//!         PlanStep::Action(t("openDoor(dishwasher)")),
//!     ],
//! };
//! // Eff± of the actions (what the PDDL domain would say).
//! let effects = |a: &Term| match a.functor() {
//!     Some("openDoor") => Effects::new(vec![t("dishwasherDoor(open)")],
//!                                      vec![t("dishwasherDoor(closed)")]),
//!     Some("navigateTo") => Effects::new(
//!         vec![Term::structure("robotAt", a.args().to_vec())], vec![]),
//!     _ => Effects::none(),
//! };
//! let e = content(&[store_used_cup, open_dishwasher_if_need], &Syntactic::new(effects))
//!     .unwrap();
//! let context: Vec<String> = e.context.iter().map(|l| l.to_string()).collect();
//! assert_eq!(context, ["used(cup1)", "not dishwasherDoor(open)", "holding(none)"]);
//! let actions: Vec<String> = e.actions.iter().map(|s| s.to_string()).collect();
//! assert_eq!(actions, ["navigateTo(dishwasher)", "openDoor(dishwasher)"]);
//!
//! // The sentence.
//! let phrases = Phrases::new([
//!     (t("navigateTo(L)"), "go to the {L}".to_string()),
//!     (t("openDoor(D)"), "open the {D}".to_string()),
//!     (t("dishwasherDoor(S)"), "the dishwasher door is {S}".to_string()),
//!     (t("holding(none)"), "my hands are free".to_string()),
//!     (t("used(C)"), "{C} is used".to_string()),
//! ]);
//! assert_eq!(
//!     sentence(&t("navigateTo(dishwasher)"), &e, &phrases),
//!     "I go to the dishwasher because cup1 is used, the dishwasher door is not open \
//!      and my hands are free: I want to open the dishwasher."
//! );
//! ```

pub mod agent;
pub mod content;
pub mod demand;
pub mod render;

pub use content::{
    atoms_meet, content, gamma, Content, ContextLiteral, Effects, FrameSnapshot, Modifies,
    PlanStep, Semantic, Syntactic,
};
pub use demand::{demand_on_adoption, demand_over, ExpectedSuccessors, Observation, Pair};
pub use render::{sentence, Phrases};
