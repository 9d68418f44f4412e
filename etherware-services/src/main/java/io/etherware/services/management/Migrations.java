package io.etherware.services.management;

import io.etherware.core.component.Shell;
import io.etherware.core.kernel.ComponentHost;
import io.etherware.core.message.Criticality;
import io.etherware.core.message.Message;
import io.etherware.core.message.Profile;
import io.etherware.core.message.QoS;
import io.etherware.services.management.AccessRule.Operation;
import io.etherware.services.management.ManagementFailure.Reason;
import io.etherware.services.management.OperationQueue.Permit;
import io.etherware.services.management.internal.LoadFailure;
import io.etherware.services.management.internal.MigrationSource;
import io.etherware.services.management.internal.MigrationTarget;

/**
 * The migrations a management service serves (the steps and the ordering argument are in the
 * package documentation): a {@link MigrateRequest} for a component of this node runs whole on the
 * worker through the {@link MigrationSource}, and the {@link MigrationStep}s of migrations into this
 * node go to the {@link MigrationTarget}: PREPARE on the steps thread, INSTALL and HANDOVER on the
 * service's dispatcher, because they are on the migration gap's path.
 *
 * <p>Threading: {@link #accept} and {@link #acceptStep} run on the service's dispatcher; the
 * migration away blocks the worker for the target's answers, so that the steps thread serves the
 * steps of another node's migration here meanwhile. Takes no lock.
 */
final class Migrations {

    private static final String MIGRATE = "migrate";

    private final ManagementContext service;
    private final ComponentHost kernel;
    private final OperationQueue worker;
    private final OperationQueue steps;
    private final MigrationSource migrationSource;
    private final MigrationTarget migrationTarget;

    /**
     * @param worker the service's worker, which runs migrations away from this node
     * @param steps  the service's thread for the PREPARE steps of migrations into this node
     * @param source the source side of migrations away from this node
     * @param target the target side of migrations into this node
     */
    Migrations(ManagementContext service, OperationQueue worker, OperationQueue steps, MigrationSource source,
               MigrationTarget target) {
        this.service = service;
        this.kernel = service.kernel();
        this.worker = worker;
        this.steps = steps;
        this.migrationSource = source;
        this.migrationTarget = target;
    }

    /** Dispatcher: refuses what the access list does not allow, else hands the migration to the worker. */
    void accept(Message message, MigrateRequest request) {
        long receivedNs = kernel.clock().nanoTime();
        if (service.refused(message, Operation.MIGRATE, MIGRATE, request.target())) {
            return;
        }
        worker.submit(permit -> migrate(message, request, receivedNs, permit),
                (reason, error) -> failMigration(message, request.target(), reason, error));
    }

    /** Worker thread: the whole migration, blocking for the target's answers. */
    private void migrate(Message message, MigrateRequest request, long receivedNs, Permit permit) {
        MigrationResult result;
        try {
            Shell shell = service.localShell(request.target());
            result = migrationSource.migrate(shell, request, message.qos(), receivedNs);
        } catch (LoadFailure e) {
            permit.release();
            failMigration(message, request.target(), e.reason(), e.getMessage());
            return;
        } catch (RuntimeException e) {
            permit.release();
            service.log().error("migration of '{}' failed unexpectedly", request.target(), e);
            failMigration(message, request.target(), Reason.SERVICE_FAILED, "the migration failed unexpectedly: " + e);
            return;
        }
        service.jarLoaders().installed(result.target(), null);
        service.counters().migrated.increment();
        service.log().info("migrated '{}' to '{}' ({} held messages): prepare {} us, quiesce {} us, transfer {} us,"
                + " relocate {} us, gap {}", result.target(), result.toNode(), result.heldMessages(),
                result.prepareNs() / 1_000, result.quiesceNs() / 1_000, result.transferNs() / 1_000,
                result.relocateNs() / 1_000, result.gapNs() < 0 ? "unknown" : result.gapNs() / 1_000 + " us");
        permit.release();
        if (message.hasSender()) {
            service.context().reply(message, result);
        }
    }

    /** Dispatcher: a step of a migration into this node, from its source's management service. */
    void acceptStep(Message message, MigrationStep step) {
        String operation = "migration " + step.phase();
        if (service.refused(message, Operation.MIGRATE, operation, step.target())) {
            return;
        }
        if (step.phase() == MigrationStep.Phase.INSTALL) {
            // On the dispatcher, like an upgrade's swap: restore and registration are on the gap's
            // path, and the class was loaded off the dispatchers by PREPARE.
            try {
                replyBehindEverything(message, migrationTarget.install(step, message.timeStamp()));
            } catch (LoadFailure e) {
                failMigration(message, step.target(), e.reason(), e.getMessage());
            } catch (RuntimeException e) {
                failMigration(message, step.target(), Reason.SERVICE_FAILED, operation + " failed: " + e);
            }
            return;
        }
        if (step.phase() == MigrationStep.Phase.HANDOVER) {
            // On the dispatcher: the hand-over is on the migration gap's path.
            try {
                migrationTarget.handover(step).whenComplete((done, error) -> {
                    if (error != null) {
                        failMigration(message, step.target(), Reason.SERVICE_FAILED, "hand-over failed: " + error);
                    } else {
                        service.counters().migratedIn.increment();
                        service.context().reply(message, done);
                    }
                });
            } catch (LoadFailure e) {
                failMigration(message, step.target(), e.reason(), e.getMessage());
            }
            return;
        }
        steps.submit(permit -> {
            MigrationStepDone done;
            try {
                done = migrationTarget.prepare(step);
            } catch (LoadFailure e) {
                permit.release();
                failMigration(message, step.target(), e.reason(), e.getMessage());
                return;
            } catch (RuntimeException e) {
                permit.release();
                failMigration(message, step.target(), Reason.SERVICE_FAILED, operation + " failed: " + e);
                return;
            }
            permit.release();
            service.context().reply(message, done);
        }, (reason, error) -> failMigration(message, step.target(), reason, error));
    }

    /**
     * The answer to an INSTALL, at the lowest criticality: the link's queue sends it after every
     * message queued before it for the source, among them those this node's senders sent to the
     * component before it was installed here. The source receives them, and forwards them back,
     * before it switches (see the package documentation). If a full queue sheds it, the source's
     * step times out and the component resumes there: nothing is lost.
     */
    private void replyBehindEverything(Message request, MigrationStepDone done) {
        if (request.hasSender()) {
            kernel.send(new Message(request.sender(), service.context().self(), kernel.clock().epochNanos(),
                    QoS.of(Criticality.NONE), done, kernel.newMessageId(), request.messageId()));
        }
    }

    private void failMigration(Message message, Profile target, Reason reason, String error) {
        service.counters().failed.increment();
        String operation = message.contents() instanceof MigrationStep step ? "migration " + step.phase() : MIGRATE;
        service.log().warn("{} request {} of '{}' failed ({}): {}", operation, message.messageId(), target, reason,
                error);
        service.reply(message, new ManagementFailure(operation, target, reason, error));
    }
}
