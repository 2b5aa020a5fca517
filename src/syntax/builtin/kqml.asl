// The plans every Jason 3 agent has for the messages its reasoning cycle does not take by
// the shortcut of TransitionSystem.applyProcMsg (an `achieve` or a `tell` of a literal):
// bdi-check's rendering of what Jason's own kqmlPlans.asl does, plan for plan, with the
// same triggers, the same number of steps (each step is one reasoning cycle) and the same
// failure handling. Where Jason's plans use namespaces and the rules of the `kqml`
// namespace, these use internal actions of bdi-check's own (`.kqml_*`), which an agent's
// own code cannot call.

// untell: the sender is no longer a source of the belief (`--b[source(Sender)]`: a new
// focus, so its `-b` event is external).
@kqmlReceivedUnTell[atomic]
+!kqml_received(Sender, untell, Content, _)
   <- .kqml_untell(Content, Sender).

// unachieve: the goal is dropped, as `.drop_desire` drops it.
@kqmlReceivedUnAchieve[atomic]
+!kqml_received(_, unachieve, Content, _)
   <- .drop_desire(Content).

// askOne of something believed: the first belief that unifies, with its annotations but
// `source(self)`, is the answer.
@kqmlReceivedAskOne1d
+!kqml_received(Sender, askOne, Content, MsgId)
   :  .kqml_answer(Content, Answer)
   <- .send(Sender, tell, Answer, MsgId).

// askOne of something not believed: a test goal, which a `+?` plan may answer.
@kqmlReceivedAskOne1c
+!kqml_received(Sender, askOne, Content, MsgId)
   <- .add_nested_source(Content, Sender, Query);
      ?Query;
      .remove_source_annot(Query, Answer);
      .send(Sender, tell, Answer, MsgId).

// The test goal failed: the answer is `untell`.
@kqmlReceivedAskOne2
-!kqml_received(Sender, askOne, Content, MsgId)[error(test_goal_failed)]
   <- .send(Sender, untell, Content, MsgId).

// askAll: every answer, in a list.
@kqmlReceivedAskAll2
+!kqml_received(Sender, askAll, Content, MsgId)
   <- .kqml_answers(Content, Answers);
      .send(Sender, tell, Answers, MsgId).

// tellHow: the told plans join the library, with the sender as their source. A plan
// travels as its key (see src/model/know_how.rs), which `.kqml_tell_how` maps to the
// plan compiled at load time.
@kqmlReceivedTellHow
+!kqml_received(Sender, tellHow, Content, _)
   <- .remove_source_annot(Content, ContentAn);
      .kqml_tell_how(ContentAn, Sender).

// untellHow: the sender is no longer a source of the plans with these labels.
@kqmlReceivedUnTellHow
+!kqml_received(Sender, untellHow, Content, _)
   <- .kqml_untell_how(Content, Sender).

// askHow: the plans relevant for the trigger, told back.
@kqmlReceivedAskHow
+!kqml_received(Sender, askHow, Content, MsgId)
   <- .kqml_relevant_plans(Content, ListOfPlans);
      .remove_source_annot(ListOfPlans, ListOfPlansAn);
      .send(Sender, tellHow, ListOfPlansAn, MsgId).

// Any other failure: printed, and nobody is answered.
@kqmlError
-!kqml_received(_, _, _, _)[error(Error)]
   <- .kqml_error(Error).
