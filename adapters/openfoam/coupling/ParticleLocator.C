#include "ParticleLocator.H"

Foam::cosim::ParticleLocator::ParticleLocator(const polyMesh& mesh)
:
    mesh_(mesh),
    bounds_(mesh.bounds()),
    maxSteps_(max(label(100), label(4*Foam::cbrt(scalar(mesh.nCells())))))
{
    // Small tolerance so points on the outer faces are not dropped by the box test
    bounds_.inflate(1e-9);
}


bool Foam::cosim::ParticleLocator::inBounds(const point& p, scalar margin) const
{
    const point& lo = bounds_.min();
    const point& hi = bounds_.max();
    return
        p.x() >= lo.x() - margin && p.x() <= hi.x() + margin
     && p.y() >= lo.y() - margin && p.y() <= hi.y() + margin
     && p.z() >= lo.z() - margin && p.z() <= hi.z() + margin;
}


Foam::label Foam::cosim::ParticleLocator::search(const point& p) const
{
    if (!inBounds(p))
    {
        return -1;
    }
    return mesh_.findCell(p);
}


Foam::label Foam::cosim::ParticleLocator::walk(const point& p, label celli) const
{
    const vectorField& Cc = mesh_.cellCentres();
    const vectorField& Cf = mesh_.faceCentres();
    const vectorField& Sf = mesh_.faceAreas();
    const labelList& own = mesh_.faceOwner();
    const labelList& nei = mesh_.faceNeighbour();
    const cellList& cells = mesh_.cells();

    for (label step = 0; step < maxSteps_; ++step)
    {
        if (mesh_.pointInCell(p, celli, polyMesh::FACE_PLANES))
        {
            return celli;
        }

        // Leave through the face the line centre -> p crosses first
        const point& c = Cc[celli];
        const vector d = p - c;
        label exitFace = -1;
        scalar lambdaMin = GREAT;
        for (const label facei : cells[celli])
        {
            const vector n = (own[facei] == celli) ? Sf[facei] : -Sf[facei];
            const scalar along = d & n;
            if (along <= VSMALL)
            {
                continue;
            }
            const scalar lambda = ((Cf[facei] - c) & n)/along;
            if (lambda < lambdaMin)
            {
                lambdaMin = lambda;
                exitFace = facei;
            }
        }
        if (exitFace < 0 || !mesh_.isInternalFace(exitFace))
        {
            return -1;
        }
        celli = (own[exitFace] == celli) ? nei[exitFace] : own[exitFace];
    }
    return -1;
}


Foam::label Foam::cosim::ParticleLocator::locate(const point& p, label seed) const
{
    if (seed >= 0 && seed < mesh_.nCells())
    {
        const label celli = walk(p, seed);
        if (celli >= 0)
        {
            return celli;
        }
    }
    return search(p);
}
