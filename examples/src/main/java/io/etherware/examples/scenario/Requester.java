package io.etherware.examples.scenario;

import io.etherware.core.component.Component;
import io.etherware.core.component.ComponentContext;
import io.etherware.core.kernel.EtherwareNode;
import io.etherware.core.message.Contents;
import io.etherware.core.message.Criticality;
import io.etherware.core.message.Message;
import io.etherware.core.message.Profile;
import io.etherware.core.message.QoS;
import java.util.Objects;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.CompletionException;
import java.util.function.Function;

/**
 * The paper's Requester (Section VI-C, Fig. 10): a component on the plant's node from which the
 * scenarios' management requests go out, so that the request is sent, and its answer received,
 * by a component at HIGH criticality, as in the paper, rather than by the scenario's own thread.
 * The scenario hands it what to ask with {@link #ask}; the request's answer completes the
 * returned future.
 *
 * <p>Thread-safety: {@link #ask} from any thread; the component runs on its dispatcher.
 */
public final class Requester implements Component {

    /** Where the scenarios add it. */
    public static final Profile PROFILE = Profile.of("scenario.requester");

    /**
     * Local only (not a registered contents type, it never leaves the node): what to ask, and
     * where the answer goes.
     *
     * @param request sends the request from the requester's context; runs on its dispatcher, so
     *                it must not block
     * @param answer  completed with the request's outcome
     * @param <T>     the answer's type
     */
    public record Ask<T>(Function<ComponentContext, CompletableFuture<T>> request, CompletableFuture<T> answer)
            implements Contents {

        /** Checks that both are given. */
        public Ask {
            Objects.requireNonNull(request, "request");
            Objects.requireNonNull(answer, "answer");
        }
    }

    /**
     * Has the requester on {@code node} send a request, at HIGH criticality.
     *
     * @param node    the node the requester was added to at {@link #PROFILE}
     * @param request sends the request from the requester's context, e.g.
     *                {@code context -> Management.migrate(context, from, request, timeout)}
     * @param <T>     the answer's type
     * @return completes with the request's outcome, on the requester's dispatcher
     */
    public static <T> CompletableFuture<T> ask(EtherwareNode node, Function<ComponentContext,
            CompletableFuture<T>> request) {
        var answer = new CompletableFuture<T>();
        node.send(PROFILE, new Ask<>(request, answer), QoS.of(Criticality.HIGH));
        return answer;
    }

    @Override
    public void onMessage(Message message, ComponentContext context) {
        if (message.contents() instanceof Ask<?> ask) {
            send(ask, context);
        }
    }

    private static <T> void send(Ask<T> ask, ComponentContext context) {
        try {
            ask.request().apply(context).whenComplete((result, error) -> {
                if (error != null) {
                    ask.answer().completeExceptionally(error instanceof CompletionException wrapped
                            && wrapped.getCause() != null ? wrapped.getCause() : error);
                } else {
                    ask.answer().complete(result);
                }
            });
        } catch (RuntimeException e) {
            ask.answer().completeExceptionally(e);
        }
    }
}
